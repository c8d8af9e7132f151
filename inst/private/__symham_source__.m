## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {[@var{src}, @var{hasacc}] =} __symham_source__ (@var{who}, @var{H}, @var{q}, @var{p}, @var{t}, @var{par}, @var{F})
## C code against symplectic_fcn.h for Hamilton's equations of @var{H}:
## f, the Hessian with its pattern, H, the batch form and (when H is
## p'M^-1 p/2 + V(q) with constant M) the acceleration; common
## subexpressions shared by SymPy's cse.  Internal.
## @end deftypefn

function [src, hasacc] = __symham_source__ (who, H, q, p, t, par, F)
  d = numel (q);
  if (isempty (t)) t = sym (0); nt = 0; else nt = 1; endif
  if (isempty (par)) parv = sym (0); np = 0; else parv = par; np = numel (par); endif
  if (isempty (F)) Fv = sym (zeros (d, 1)); else Fv = F; endif
  cmd = {
    '(H, q, p, t, par, F, d, nt, npar) = _ins'
    'import sympy as S'
    'd = int(d); nt = int(nt); npar = int(npar)'
    'L = lambda x: list(x) if getattr(x, "is_Matrix", False) else [x]'
    'q = L(q); p = L(p); F = L(F)'
    'par = L(par) if npar > 0 else []'
    'sub = {}'
    'for i in range(d):'
    '    sub[q[i]] = S.Symbol("y[%d]" % i)'
    '    sub[p[i]] = S.Symbol("y[%d]" % (d + i))'
    'for k in range(npar):'
    '    sub[par[k]] = S.Symbol("par[%d]" % k)'
    'if nt:'
    '    sub[t] = S.Symbol("t")'
    'H = S.sympify(H); F = [S.sympify(e) for e in F]'
    'known = set(sub.keys())'
    'free = set()'
    'for e in [H] + F:'
    '    free |= e.free_symbols - known'
    'if free:'
    '    return "unbound: " + ", ".join(sorted(str(s) for s in free)), False'
    'y = q + p'
    'dH = [S.diff(H, v) for v in y]'
    'f = dH[d:] + [-dH[i] + F[i] for i in range(d)]'
    'hes = []; rows = []; cols = []'
    'for j in range(2 * d):'
    '    for i in range(2 * d):'
    '        e = S.diff(dH[i], y[j])'
    '        if e != 0:'
    '            hes.append(e); rows.append(i); cols.append(j)'
    'from sympy.printing.c import C99CodePrinter'
    'class Printer(C99CodePrinter):'
    '    # small integer and half-integer powers as products and sqrt: pow'
    '    # (r2, 3.0/2.0) costs several times r2*sqrt(r2) at -O2'
    '    def _print_Pow(self, e):'
    '        b, x = e.base, e.exp'
    '        if x.is_Rational and x.q in (1, 2) and 0 < abs(x.p) <= 16:'
    '            bs = "(%s)" % self._print(b)'
    '            f = [bs] * (abs(x.p) // x.q if x.q == 1 else (abs(x.p) - 1) // 2)'
    '            if x.q == 2:'
    '                f.append("sqrt%s" % bs)'
    '            r = "*".join(f)'
    '            return "(1.0/(%s))" % r if x.p < 0 else "(%s)" % r'
    '        return C99CodePrinter._print_Pow(self, e)'
    'ccode = Printer().doprint'
    'def body(exprs, outs, ret):'
    '    rep, red = S.cse([e.xreplace(sub) for e in exprs])'
    '    s = ""'
    '    for (a, b) in rep:'
    '        s += "  const double %s = %s;\n" % (ccode(a), ccode(b))'
    '    for (o, e) in zip(outs, red):'
    '        s += "  %s = %s;\n" % (o, ccode(e))'
    '    return s + "  return " + ret + ";\n"'
    'c = "#include <math.h>\n#include \"symplectic_fcn.h\"\n"'
    'c += "SYMPLECTIC_SYSTEM (%d, %d);\n" % (d, npar)'
    'c += "int symplectic_f (double t, const double *y, double *dy, const double *par)\n{\n"'
    'c += "  (void) t; (void) par;\n"'
    'c += body(f, ["dy[%d]" % i for i in range(2 * d)], "0") + "}\n"'
    'c += "int symplectic_f_batch (int k, const double *t, const double *y, double *dy, const double *par)\n{\n"'
    'c += "  for (int j = 0; j < k; j++) {\n    int r = symplectic_f (t[j], y + (long) j * %d, dy + (long) j * %d, par);\n    if (r) return r;\n  }\n  return 0;\n}\n" % (2 * d, 2 * d)'
    'colptr = [sum(1 for cj in cols if cj < j) for j in range(2 * d + 1)]'
    'c += "int symplectic_hess_pattern (int *colptr, int *rowind)\n{\n"'
    'c += "  static const int cp[] = {%s};\n" % ", ".join(str(v) for v in colptr)'
    'c += "  static const int ri[] = {%s};\n" % ", ".join(str(v) for v in (rows or [0]))'
    'c += "  if (colptr) for (int j = 0; j <= %d; j++) colptr[j] = cp[j];\n" % (2 * d)'
    'c += "  if (rowind) for (int j = 0; j < %d; j++) rowind[j] = ri[j];\n" % len(rows)'
    'c += "  return %d;\n}\n" % len(rows)'
    'c += "int symplectic_hess (double t, const double *y, double *val, const double *par)\n{\n"'
    'c += "  (void) t; (void) y; (void) par;\n"'
    'c += body(hes, ["val[%d]" % i for i in range(len(hes))], "0") + "}\n"'
    'rep, red = S.cse([H.xreplace(sub)])'
    'c += "double symplectic_energy (double t, const double *y, const double *par)\n{\n"'
    'c += "  (void) t; (void) y; (void) par;\n"'
    'for (a, b) in rep:'
    '    c += "  const double %s = %s;\n" % (ccode(a), ccode(b))'
    'c += "  return %s;\n}\n" % ccode(red[0])'
    'M = S.Matrix(2 * d, 2 * d, lambda i, j: S.diff(dH[i], y[j]))[d:, d:]'
    'pz = {v: 0 for v in p}'
    'V = H.subs(pz)'
    'pv = S.Matrix(p)'
    'quad = all(e.free_symbols <= set(par) for e in M) and S.expand(H - V - (pv.T * M * pv)[0] / 2) == 0'
    'quad = quad and all(not (e.free_symbols & set(p)) for e in F)'
    'acc = False'
    'if quad and M.det() != 0:'
    '    g = S.Matrix([-S.diff(V, v) + F[i] for i, v in enumerate(q)])'
    '    a = M * g'
    '    qsub = {S.Symbol("y[%d]" % i): S.Symbol("q[%d]" % i) for i in range(d)}'
    '    c += "int symplectic_accel (double t, const double *q, double *a, const double *par)\n{\n"'
    '    c += "  (void) t; (void) par;\n"'
    '    c += body([e.xreplace(sub).xreplace(qsub) for e in a], ["a[%d]" % i for i in range(d)], "0").replace("y[", "q[") + "}\n"'
    '    acc = True'
    'return c, acc'
  };
  [src, hasacc] = pycall_sympy__ (cmd, H, q, p, t, parv, Fv, d, nt, np);
  if (strncmp (src, "unbound: ", 9))
    error ("Octave:invalid-input-arg",
           "%s: symbols not bound (neither in Q, P, Time nor Parameters): %s",
           who, src(10:end));
  endif
endfunction
