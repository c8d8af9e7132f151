/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* coroutine.h -- internal to the driver: a function run on a stack of
   its own, on the caller's thread (coroutine.c). */
#ifndef SYM_COROUTINE_H
#define SYM_COROUTINE_H

#include <stddef.h>

#if ! defined (__x86_64__)
#include <ucontext.h>
#endif

typedef struct {
  void *stack;
  size_t size;
  void (*fn) (void *);
  void *arg;
  int finished;             /* fn has returned */
  void (*out_fn) (void *);  /* a call to make from the caller's stack */
  void *out_arg;
#if defined (__x86_64__)
  void *sp, *caller_sp;
#else
  ucontext_t self, caller;
#endif
  unsigned vg_id;           /* the stack's number for valgrind */
  /* AddressSanitizer's bookkeeping of the switches */
  void *fake;
  const void *caller_bottom;
  size_t caller_size;
} sym_co;

/* co will run fn (arg) on stack (size bytes) from its first resume;
   returns 0, or -1 if the context cannot be made */
int sym_co_init (sym_co *co, void *stack, size_t size, void (*fn) (void *),
                 void *arg);
/* run co until it yields or its fn returns (co->finished; it must not be
   resumed again); the calls co asks for by sym_outside (numerics.h) are
   made on the way, from the caller's stack */
void sym_co_resume (sym_co *co);
/* from inside co: back to the resume that ran it */
void sym_co_yield (sym_co *co);
/* co's stack is no longer co's (co has finished, or never started) */
void sym_co_release (sym_co *co);

#endif
