/* test_spvi_kepler.c -- long-time behaviour of SPVI (4,3) at a fixed step
   on the Kepler problem, e = 0.6, h = 2 pi/100, 1000 periods (100000
   steps): bounded energy error, angular momentum conserved to round-off,
   and the cost per step (Newton iterations, rhs and jac calls). */
#include "sym.h"
#include "testutil.h"
#include "test_spvi_systems.h"

#include <time.h>

int
main (void)
{
  const double e = 0.6, h = 2 * TS_PI / 100;
  const long per_period = 100, periods = 1000;
  const long nsteps = per_period * periods, window = 100 * per_period;
  sym_system sys = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_method_opts o = ts_opts (4, 3);
  int st;
  void *s = sym_step_spvi->alloc (&sys, &o, &st);
  CHECK (s != NULL, "alloc: %d", st);
  if (! s)
    return tu_finish ("test_spvi_kepler");

  double y[4], yn[4];
  ts_kep_y0 (e, y);
  const double H0 = ts_kep_H (y), L0 = ts_kep_L (y);
  double efirst = 0.0, elast = 0.0, lerr = 0.0, t = 0.0;
  clock_t c0 = clock ();
  for (long k = 0; k < nsteps; k++)
    {
      double tn = h * (double) (k + 1);
      st = sym_step_spvi->step (s, &sys, t, tn - t, y, yn, NULL);
      if (st)
        break;
      sym_step_spvi->accept (s);
      memcpy (y, yn, sizeof y);
      t = tn;
      double de = fabs ((ts_kep_H (y) - H0) / H0);
      if (k < window)
        efirst = fmax (efirst, de);
      if (k >= nsteps - window)
        elast = fmax (elast, de);
      lerr = fmax (lerr, fabs ((ts_kep_L (y) - L0) / L0));
    }
  double secs = (double) (clock () - c0) / CLOCKS_PER_SEC;
  CHECK (st == 0, "step failed: %d (%s) at t = %g", st, sym_status_name (st),
         t);
  const sym_counters *c = &sys.cnt;
  double it = (double) c->nnewton / nsteps, rhs = (double) c->nrhs / nsteps;
  double jac = (double) c->njac / nsteps, lu = (double) c->nlu / nsteps;
  printf ("Kepler e = 0.6, (4,3), h = 2pi/100, %ld periods, %.2f s:\n"
          "  relative energy error: max %.3e over the first 100 periods, "
          "%.3e over the last 100 (ratio %.3f)\n"
          "  relative angular momentum error: %.2e\n"
          "  per step: %.3f Newton iterations, %.3f rhs calls, %.4f jac "
          "calls, %.4f LU\n", periods, secs, efirst, elast, elast / efirst,
          lerr, it, rhs, jac, lu);
  CHECK (elast <= 1.5 * efirst, "energy error grows: %.3g -> %.3g", efirst,
         elast);
  CHECK (efirst < 1e-6, "energy error %.3g", efirst);
  CHECK (lerr <= 1e-12, "angular momentum error %.3g", lerr);
  /* the cost stays where it was measured (4.07 iterations, 12.2 rhs and
     0.42 jac calls per step) */
  CHECK (it < 4.5 && rhs < 13.5 && jac < 0.6, "cost per step: %.3f it, "
         "%.3f rhs, %.3f jac", it, rhs, jac);
  CHECK (c->nnewton_fail == 0, "%ld Newton failures", c->nnewton_fail);

  sym_step_spvi->free (s);
  return tu_finish ("test_spvi_kepler");
}
