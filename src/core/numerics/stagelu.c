/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* stagelu.c -- the LU of M = I - gamma J for Newton's staged solves,
   gamma = gr + i gi: dense by LAPACK (dgetrf/dgetrs, zgetrf/zgetrs), or
   sparse by KLU (SuiteSparse), real when gi = 0 and complex otherwise.

   Sparse: M's pattern is J's with the whole diagonal added (rows sorted
   in each column), so that it is the same for every gamma; KLU's
   symbolic analysis of it is kept while J's pattern stays the same, and
   serves real and complex factors alike.

   KLU's memory: this KLU (1.3, SuiteSparse 5) has no allocator of its
   own in klu_common; it allocates through the process-wide
   SuiteSparse_config hooks.  Those are pointed at sym_malloc for the
   length of each KLU call and restored right after (the core is single
   threaded and no user code runs inside KLU), so that KLU's objects,
   and the workspace of the orderings it calls, come from sym_malloc.
   (An allocator that does not return when it fails would leave them
   in: the MEX one returns NULL for large blocks.) */
#include "numerics.h"

#include <math.h>
#include <string.h>
#include <limits.h>
#include <stdint.h>

#include <suitesparse/klu.h>

/* ------------------------------------------------------------ KLU's memory */
/* SuiteSparse_config (-lsuitesparseconfig) holds the hooks up to
   SuiteSparse 6; where the struct is no longer public (SuiteSparse 7)
   KLU keeps its own allocator */
#if defined (SUITESPARSE_MAIN_VERSION) && SUITESPARSE_MAIN_VERSION < 7
#define SS_CONFIG (&SuiteSparse_config)
#else
#define SS_CONFIG ((struct SuiteSparse_config_struct *) NULL)
#endif

/* a size header in front of each block, so that realloc can copy; 16
   bytes keep the block as aligned as sym_malloc's */
#define SS_HEADER 16

static void *
ss_malloc (size_t nbytes)
{
  if (nbytes > SIZE_MAX - SS_HEADER)
    return NULL;
  unsigned char *p = sym_malloc (nbytes + SS_HEADER);
  if (! p)
    return NULL;
  memcpy (p, &nbytes, sizeof nbytes);
  return p + SS_HEADER;
}

static void
ss_free (void *ptr)
{
  if (ptr)
    sym_free ((unsigned char *) ptr - SS_HEADER);
}

static void *
ss_calloc (size_t count, size_t size)
{
  if (size && count > SIZE_MAX / size)
    return NULL;
  void *p = ss_malloc (count * size);
  if (p)
    memset (p, 0, count * size);
  return p;
}

/* realloc's contract: NULL on failure with ptr left as it was.  A
   block that shrinks stays as it is (its header keeps the true size):
   KLU trims its factors so, and nothing is gained by a copy */
static void *
ss_realloc (void *ptr, size_t nbytes)
{
  if (! ptr)
    return ss_malloc (nbytes);
  size_t old;
  memcpy (&old, (unsigned char *) ptr - SS_HEADER, sizeof old);
  if (nbytes <= old)
    return ptr;
  void *p = ss_malloc (nbytes);
  if (! p)
    return NULL;
  memcpy (p, ptr, old);
  ss_free (ptr);
  return p;
}

/* the hooks a KLU call found, to be put back (cfg NULL: none) */
typedef struct {
  struct SuiteSparse_config_struct *cfg;
  void *(*m) (size_t);
  void *(*c) (size_t, size_t);
  void *(*r) (void *, size_t);
  void (*f) (void *);
} ss_hooks;

/* our hooks in for one KLU call */
static ss_hooks
ss_enter (void)
{
  ss_hooks saved = { SS_CONFIG, NULL, NULL, NULL, NULL };
  struct SuiteSparse_config_struct *cfg = saved.cfg;
  if (! cfg)
    return saved;
  saved.m = cfg->malloc_func;
  saved.c = cfg->calloc_func;
  saved.r = cfg->realloc_func;
  saved.f = cfg->free_func;
  cfg->malloc_func = ss_malloc;
  cfg->calloc_func = ss_calloc;
  cfg->realloc_func = ss_realloc;
  cfg->free_func = ss_free;
  return saved;
}

static void
ss_leave (const ss_hooks *saved)
{
  struct SuiteSparse_config_struct *cfg = saved->cfg;
  if (! cfg)
    return;
  cfg->malloc_func = saved->m;
  cfg->calloc_func = saved->c;
  cfg->realloc_func = saved->r;
  cfg->free_func = saved->f;
}

/* --------------------------------------------------------------- KLU state */
typedef struct {
  klu_common common;
  klu_symbolic *symbolic;
  klu_numeric *numeric;
  int jnnz;            /* J's pattern as last analysed (symbolic != NULL) */
  int *jcolptr;        /* n + 1 */
  int *jrowind;        /* cap */
  int *mcolptr;        /* n + 1: M's pattern */
  int *mrowind;        /* cap */
  double *mval;        /* 2 cap: M's values, complex ones interleaved */
  int cap;             /* room in jrowind, mrowind and mval */
  int ncplx;           /* numeric holds complex factors */
  double rcond;        /* its pivots' ratio at the last full factor */
} stage_klu;

static void
klu_drop_numeric (stage_klu *k)
{
  if (! k->numeric)
    return;
  ss_hooks h = ss_enter ();
  klu_free_numeric (&k->numeric, &k->common);   /* real or complex alike */
  ss_leave (&h);
  k->numeric = NULL;
}

static void
klu_drop_symbolic (stage_klu *k)
{
  klu_drop_numeric (k);
  if (! k->symbolic)
    return;
  ss_hooks h = ss_enter ();
  klu_free_symbolic (&k->symbolic, &k->common);
  ss_leave (&h);
  k->symbolic = NULL;
}

static void
klu_state_free (stage_klu *k)
{
  if (! k)
    return;
  klu_drop_symbolic (k);
  sym_free (k->jcolptr);
  sym_free (k->jrowind);
  sym_free (k->mcolptr);
  sym_free (k->mrowind);
  sym_free (k->mval);
  sym_free (k);
}

static stage_klu *
klu_state_new (int n)
{
  stage_klu *k = sym_calloc (1, sizeof (*k));
  if (! k)
    return NULL;
  klu_defaults (&k->common);       /* sets parameters, allocates nothing */
  k->jcolptr = sym_calloc ((size_t) n + 1, sizeof (int));
  k->mcolptr = sym_calloc ((size_t) n + 1, sizeof (int));
  if (! k->jcolptr || ! k->mcolptr)
    {
      klu_state_free (k);
      return NULL;
    }
  return k;
}

/* room for cap entries of J and of M (old contents dropped) */
static int
klu_room (stage_klu *k, int cap)
{
  if (cap <= k->cap)
    return SYM_SUCCESS;
  klu_drop_symbolic (k);           /* its pattern goes with jrowind */
  sym_free (k->jrowind);
  sym_free (k->mrowind);
  sym_free (k->mval);
  k->cap = 0;
  k->jrowind = sym_malloc ((size_t) cap * sizeof (int));
  k->mrowind = sym_malloc ((size_t) cap * sizeof (int));
  k->mval = sym_malloc ((size_t) cap * 2 * sizeof (double));
  if (! k->jrowind || ! k->mrowind || ! k->mval)
    return SYM_ENOMEM;
  k->cap = cap;
  return SYM_SUCCESS;
}

/* ---------------------------------------------------------------- sparse M */
/* J is n-by-n with increasing rows in each column; its values finite */
static int
csc_check (const sym_csc *J, int n, int *finite)
{
  if (! J || J->n != n || ! J->colptr || J->colptr[0] != 0)
    return SYM_EBADINPUT;
  *finite = 1;
  for (int j = 0; j < n; j++)
    {
      int k0 = J->colptr[j], k1 = J->colptr[j + 1];
      if (k1 < k0 || (k1 > k0 && (! J->rowind || ! J->val)))
        return SYM_EBADINPUT;
      for (int k = k0; k < k1; k++)
        {
          if (J->rowind[k] < (k > k0 ? J->rowind[k - 1] + 1 : 0)
              || J->rowind[k] >= n)
            return SYM_EBADINPUT;
          if (! isfinite (J->val[k]))
            *finite = 0;
        }
    }
  return SYM_SUCCESS;
}

static int
klu_same_pattern (const stage_klu *k, const sym_csc *J, int n)
{
  int nz = J->colptr[n];
  return k->symbolic && nz == k->jnnz
         && ! memcmp (k->jcolptr, J->colptr, ((size_t) n + 1) * sizeof (int))
         && (nz == 0 || ! memcmp (k->jrowind, J->rowind,
                                  (size_t) nz * sizeof (int)));
}

/* one entry of M = I - gamma J: diag (0 or 1) - gamma v, at m (1 or 2
   doubles) */
static void
m_entry (double *m, int cplx, double diag, double v, double gr, double gi)
{
  m[0] = diag - gr * v;
  if (cplx)
    m[1] = -gi * v;
}

/* entry p of M: row i, value diag - gamma v */
static void
m_put (stage_klu *k, int p, int i, int cplx, double diag, double v,
       double gr, double gi)
{
  k->mrowind[p] = i;
  m_entry (k->mval + (cplx ? 2 : 1) * (size_t) p, cplx, diag, v, gr, gi);
}

/* M's pattern (J's and the diagonal, rows increasing) and values; finite
   unless gamma J overflows */
static int
m_fill (stage_klu *k, const sym_csc *J, int n, int cplx, double gr,
        double gi)
{
  int p = 0, finite = 1;
  for (int j = 0; j < n; j++)
    {
      int diag = 0;
      k->mcolptr[j] = p;
      for (int q = J->colptr[j]; q < J->colptr[j + 1]; q++)
        {
          int i = J->rowind[q];
          if (! diag && i > j)
            {
              m_put (k, p++, j, cplx, 1.0, 0.0, gr, gi);
              diag = 1;
            }
          m_put (k, p++, i, cplx, i == j, J->val[q], gr, gi);
          diag |= (i == j);
        }
      if (! diag)
        m_put (k, p++, j, cplx, 1.0, 0.0, gr, gi);
    }
  k->mcolptr[n] = p;
  for (size_t q = 0; q < (cplx ? 2 : 1) * (size_t) p; q++)
    if (! isfinite (k->mval[q]))
      finite = 0;
  return finite;
}

/* KLU's status after a failed call as ours */
static int
klu_status (const klu_common *c)
{
  switch (c->status)
    {
    case KLU_OUT_OF_MEMORY:
    case KLU_TOO_LARGE:
      return SYM_ENOMEM;
    case KLU_INVALID:
      return SYM_EBADINPUT;
    default:
      return SYM_SINGULAR;
    }
}

/* KLU's symbolic analysis of M's pattern (J's saved with it) */
static int
klu_analyse (stage_klu *k, const sym_csc *J, int n)
{
  klu_drop_symbolic (k);
  /* the workspace of the orderings (AMD, BTF) comes through the hooks
     too, and goes back before the call returns */
  ss_hooks h = ss_enter ();
  k->symbolic = klu_analyze (n, k->mcolptr, k->mrowind, &k->common);
  ss_leave (&h);
  if (! k->symbolic)
    return klu_status (&k->common);
  k->jnnz = J->colptr[n];
  memcpy (k->jcolptr, J->colptr, ((size_t) n + 1) * sizeof (int));
  if (k->jnnz > 0)
    memcpy (k->jrowind, J->rowind, (size_t) k->jnnz * sizeof (int));
  return SYM_SUCCESS;
}

/* The factors again in the pivot order of the last full factorization
   (no allocation), while the pivots' ratio (KLU's rcond) stays within
   SYM_KLU_REFACTOR of that one's; 0 if not done */
static int
klu_again (stage_klu *k, int cplx)
{
  if (! k->numeric || k->ncplx != cplx)
    return 0;
  ss_hooks h = ss_enter ();
  int ok = cplx ? klu_z_refactor (k->mcolptr, k->mrowind, k->mval,
                                  k->symbolic, k->numeric, &k->common)
                  && klu_z_rcond (k->symbolic, k->numeric, &k->common)
                : klu_refactor (k->mcolptr, k->mrowind, k->mval,
                                k->symbolic, k->numeric, &k->common)
                  && klu_rcond (k->symbolic, k->numeric, &k->common);
  ss_leave (&h);
  return ok && k->common.status == KLU_OK
         && k->common.rcond >= SYM_KLU_REFACTOR * k->rcond;
}

static int
sparse_factor (sym_stage_lu *s, double gr, double gi, const sym_csc *J)
{
  stage_klu *k = s->klu;
  int n = s->n, finite, st = csc_check (J, n, &finite);
  if (st != SYM_SUCCESS)
    return st;
  if (! finite)
    return SYM_SINGULAR;
  if (J->colptr[n] > INT_MAX - n)
    return SYM_ENOMEM;
  st = klu_room (k, J->colptr[n] + n);
  if (st != SYM_SUCCESS)
    return st;
  if (! m_fill (k, J, n, s->cplx, gr, gi))
    {
      klu_drop_numeric (k);
      return SYM_SINGULAR;
    }
  if (! klu_same_pattern (k, J, n)
      && (st = klu_analyse (k, J, n)) != SYM_SUCCESS)
    return st;
  if (klu_again (k, s->cplx))
    return SYM_SUCCESS;
  klu_drop_numeric (k);
  ss_hooks h = ss_enter ();
  k->numeric = s->cplx ? klu_z_factor (k->mcolptr, k->mrowind, k->mval,
                                       k->symbolic, &k->common)
                       : klu_factor (k->mcolptr, k->mrowind, k->mval,
                                     k->symbolic, &k->common);
  if (k->numeric)
    {
      k->ncplx = s->cplx;
      if (! (s->cplx ? klu_z_rcond (k->symbolic, k->numeric, &k->common)
                     : klu_rcond (k->symbolic, k->numeric, &k->common)))
        k->common.rcond = 0.0;
      k->rcond = k->common.rcond;
    }
  ss_leave (&h);
  if (! k->numeric)
    return klu_status (&k->common);
  /* a warning with factors (no singular stop here) is still singular */
  if (k->common.status != KLU_OK)
    {
      klu_drop_numeric (k);
      return SYM_SINGULAR;
    }
  return SYM_SUCCESS;
}

static int
sparse_solve (sym_stage_lu *s, double *b)
{
  stage_klu *k = s->klu;
  ss_hooks h = ss_enter ();
  int ok = s->cplx ? klu_z_solve (k->symbolic, k->numeric, s->n, 1, b,
                                  &k->common)
                   : klu_solve (k->symbolic, k->numeric, s->n, 1, b,
                                &k->common);
  ss_leave (&h);
  return ok ? SYM_SUCCESS : SYM_EBADINPUT;
}

/* ---------------------------------------------------------------- dense M */
/* M = I - gamma J into s->a (real, or complex interleaved); 0 when an
   entry is not finite (J's NaN, or gamma J overflowing) */
static int
dense_fill (sym_stage_lu *s, double gr, double gi, const double *J, int ld)
{
  int n = s->n, w = s->cplx ? 2 : 1, finite = 1;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      {
        double *m = s->a + w * ((size_t) j * n + i);
        m_entry (m, s->cplx, i == j, J[(size_t) j * ld + i], gr, gi);
        if (! isfinite (m[0]) || (s->cplx && ! isfinite (m[1])))
          finite = 0;
      }
  return finite;
}

static int
dense_factor (sym_stage_lu *s, double gr, double gi, const double *J,
              int ld)
{
  int info = 0;
  if (! J || ld < s->n)
    return SYM_EBADINPUT;
  /* no factors of a non-finite matrix: as for a singular one */
  if (! dense_fill (s, gr, gi, J, ld))
    return SYM_SINGULAR;
  info = sym_getrf (s->cplx, s->n, s->a, s->ipiv);
  if (info > 0)
    return SYM_SINGULAR;
  return info == 0 ? SYM_SUCCESS : SYM_EBADINPUT;
}

static int
dense_solve (sym_stage_lu *s, double *b)
{
  int info = sym_getrs (s->cplx, s->n, s->a, s->ipiv, b);
  return info == 0 ? SYM_SUCCESS : SYM_EBADINPUT;
}

/* ---------------------------------------------------------------- public */
int
sym_stage_lu_init (sym_stage_lu *s, int n, int sparse)
{
  memset (s, 0, sizeof (*s));
  if (n < 1)
    return SYM_EBADINPUT;
  if (! sparse && (size_t) n > SIZE_MAX / (2 * sizeof (double)) / n)
    return SYM_ENOMEM;
  s->n = n;
  s->sparse = sparse != 0;
  if (s->sparse)
    s->klu = klu_state_new (n);
  else
    {
      /* room for complex factors: a later complex factor allocates
         nothing */
      s->a = sym_malloc ((size_t) n * n * 2 * sizeof (double));
      s->ipiv = sym_malloc ((size_t) n * sizeof (int));
    }
  if (s->sparse ? ! s->klu : (! s->a || ! s->ipiv))
    {
      sym_stage_lu_free (s);
      return SYM_ENOMEM;
    }
  return SYM_SUCCESS;
}

void
sym_stage_lu_free (sym_stage_lu *s)
{
  klu_state_free (s->klu);
  sym_free (s->a);
  sym_free (s->ipiv);
  s->klu = NULL;
  s->a = NULL;
  s->ipiv = NULL;
  s->factored = 0;
}

int
sym_stage_lu_factor (sym_stage_lu *s, double gr, double gi,
                     const double *J, int ld, const sym_csc *Js,
                     sym_counters *c)
{
  if (c)
    c->nlu++;
  s->factored = 0;
  if (s->sparse ? ! s->klu : ! s->a)
    return SYM_EBADINPUT;
  s->cplx = gi != 0;
  int st = s->sparse ? sparse_factor (s, gr, gi, Js)
                     : dense_factor (s, gr, gi, J, ld);
  s->factored = (st == SYM_SUCCESS);
  return st;
}

int
sym_stage_lu_solve (sym_stage_lu *s, double *b, sym_counters *c)
{
  if (! s->factored)
    return SYM_EBADINPUT;
  if (c)
    c->nsolve++;
  return s->sparse ? sparse_solve (s, b) : dense_solve (s, b);
}
