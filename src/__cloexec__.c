/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* __cloexec__.c -- MEX entry point that marks every open file descriptor
   of this process above stderr close-on-exec:

     n = __cloexec__ ()     n: how many descriptors it marked

   A Parallel run calls it before the parallel package starts its
   processes.  Without it they inherit every pipe this process holds, among
   them the one to the symbolic package's Python: Python then never sees
   the end of its input, and Octave's exit, which waits for Python, hangs.
   The pipes the parallel package makes for a new process are made after
   this call, so that process still gets them.  Where descriptors cannot be
   listed (no /proc/self/fd) it marks 3 to 1023.  */
/* dirfd, fcntl: POSIX.1-2008 (the build is -std=c99) */
#define _POSIX_C_SOURCE 200809L
#include "mex.h"

#if defined(__unix__) || defined(__APPLE__)
#include <dirent.h>
#include <fcntl.h>
#include <stdlib.h>

static int
mark (int fd)
{
  const int fl = fcntl (fd, F_GETFD);
  if (fl < 0 || (fl & FD_CLOEXEC))
    return 0;
  return fcntl (fd, F_SETFD, fl | FD_CLOEXEC) == 0;
}

static int
mark_all (void)
{
  int n = 0;
  DIR *d = opendir ("/proc/self/fd");
  if (! d)
    {
      for (int fd = 3; fd < 1024; fd++)
        n += mark (fd);
      return n;
    }
  const int own = dirfd (d);
  struct dirent *e;
  while ((e = readdir (d)) != NULL)
    {
      char *end;
      const long fd = strtol (e->d_name, &end, 10);
      if (end != e->d_name && *end == '\0' && fd > 2 && fd != own)
        n += mark ((int) fd);
    }
  closedir (d);
  return n;
}
#else
static int
mark_all (void)
{
  return 0;
}
#endif

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  (void) prhs;
  if (nrhs != 0 || nlhs > 1)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call",
                       "__cloexec__: takes no argument, returns one value");
  plhs[0] = mxCreateDoubleScalar (mark_all ());
}
