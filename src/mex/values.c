/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* values.c -- what an Octave value is: its size, whether it names a
   function, its full and double forms. */
#include "symmex.h"

int
symmex_is_size (const mxArray *a, size_t r, size_t k)
{
  return mxGetNumberOfDimensions (a) == 2 && mxGetM (a) == r
         && mxGetN (a) == k;
}

int
symmex_is_vector (const mxArray *a)
{
  return mxGetNumberOfDimensions (a) == 2
         && (mxGetM (a) == 1 || mxGetN (a) == 1);
}

/* Octave 7 keeps a diagonal or permutation matrix, a range or a complex
   value in a form of its own: mxGetPr converts it, and leaks a little
   when its dimensions were asked for before (bench/NOTES.md).  Its data
   asked for first, before anything else, converts it with no leak; a
   full double matrix only hands its pointer over. */
void
symmex_settle (const mxArray *a)
{
  if (a && (mxIsNumeric (a) || mxIsLogical (a)) && ! mxIsSparse (a))
    (void) mxGetData (a);
}

mxArray *
symmex_full (const mxArray *a)
{
  if (! a || ! mxIsSparse (a))
    {
      symmex_settle (a);
      return (mxArray *) a;
    }
  mxArray *in[1] = { (mxArray *) a }, *out[1] = { NULL };
  mexCallMATLAB (1, out, 1, in, "full");
  symmex_settle (out[0]);
  return out[0];
}

int
symmex_is_function (const mxArray *a)
{
  if (mxIsFunctionHandle (a))
    return 1;
  if (mxIsChar (a) && mxGetM (a) == 1 && mxGetN (a) > 0)
    {
      mxArray *in[1] = { (mxArray *) a }, *out[1] = { NULL };
      mexCallMATLAB (1, out, 1, in, "exist");
      double e = mxGetScalar (out[0]);
      mxDestroyArray (out[0]);
      if (e == 3 || e == 5 || e == 103)
        return 1;
      if (e != 2)
        return 0;
      /* 2 is any file on the path, a script too: nargin knows functions */
      out[0] = NULL;
      mxArray *ex = mexCallMATLABWithTrap (1, out, 1, in, "nargin");
      if (ex)
        {
          mxDestroyArray (ex);
          return 0;
        }
      mxDestroyArray (out[0]);
      return 1;
    }
  return 0;
}

mxArray *
symmex_to_double (const mxArray *a)
{
  mxArray *in[1] = { (mxArray *) a }, *out[1] = { NULL };
  mexCallMATLAB (1, out, 1, in, "double");
  /* double of a float diagonal matrix is a diagonal one */
  symmex_settle (out[0]);
  return out[0];
}

/* A value returned by a user's function, replaced in *pa by its full
   form (sparse values are taken as full), or by its double form (a
   numeric, logical or char value); the replaced array is destroyed. */
mxArray *
symmex_take_full (mxArray **pa)
{
  mxArray *a = *pa;
  if (a && mxIsSparse (a))
    {
      *pa = symmex_full (a);
      mxDestroyArray (a);
    }
  return *pa;
}

mxArray *
symmex_take_double (mxArray **pa)
{
  mxArray *a = *pa;
  if (! mxIsDouble (a))
    {
      *pa = symmex_to_double (a);
      mxDestroyArray (a);
    }
  return *pa;
}

