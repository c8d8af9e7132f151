/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* coroutine.c -- stacks of their own for the members of an ensemble
   (ensemble.c), on one thread: a member runs until it needs the caller
   (an evaluation), the caller runs until it resumes the member.

   On x86-64 the switch saves the callee-saved registers and the stack
   pointer, a few instructions; elsewhere it is swapcontext, which also
   saves the signal mask by a system call and costs about as much as a
   step of a small member.  Under AddressSanitizer every switch is
   announced to it, so that it knows which stack is in use. */
#if ! defined (__x86_64__)
#define _XOPEN_SOURCE 600
#endif
#include "coroutine.h"
#include "../numerics/numerics.h"

#include <stdint.h>
#include <string.h>

#if defined (__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#define CO_ASAN 1
#else
#define CO_ASAN 0
#endif

/* valgrind is told of each stack (a no-op outside it), so that it takes
   a switch for a switch and not for a huge frame */
#if defined (__has_include)
#if __has_include (<valgrind/memcheck.h>)
#include <valgrind/memcheck.h>
#define CO_VALGRIND 1
#endif
#endif

#if defined (__x86_64__)
/* sym_co_swap (&save, to): pushes rbp, rbx, r12-r15 and the MXCSR and
   x87 control words (the SysV ABI's callee-saved state), stores rsp in
   *save, loads to as rsp and pops the same from there */
void sym_co_swap (void **save, void *to);
__asm__ (".text\n"
         ".p2align 4\n"
         ".type sym_co_swap, @function\n"
         "sym_co_swap:\n"
         "  pushq %rbp\n  pushq %rbx\n  pushq %r12\n"
         "  pushq %r13\n  pushq %r14\n  pushq %r15\n"
         "  subq $8, %rsp\n  stmxcsr (%rsp)\n  fnstcw 4(%rsp)\n"
         "  movq %rsp, (%rdi)\n"
         "  movq %rsi, %rsp\n"
         "  ldmxcsr (%rsp)\n  fldcw 4(%rsp)\n  addq $8, %rsp\n"
         "  popq %r15\n  popq %r14\n  popq %r13\n"
         "  popq %r12\n  popq %rbx\n  popq %rbp\n"
         "  ret\n"
         ".size sym_co_swap, .-sym_co_swap\n");
#endif

/* the coroutine being started, read by its first frame; the one
   running (NULL: the caller's stack is in use) */
static sym_co *co_starting, *co_current;

#if CO_ASAN
static void
co_asan_enter (sym_co *co)
{
  /* now on co's stack: the caller's stack is where it came from */
  __sanitizer_finish_switch_fiber (co->fake, &co->caller_bottom,
                                   &co->caller_size);
}
#endif

static void
co_first (void)
{
  sym_co *co = co_starting;
#if CO_ASAN
  co_asan_enter (co);
#endif
  co->fn (co->arg);
  co->finished = 1;
#if CO_ASAN
  __sanitizer_start_switch_fiber (NULL, co->caller_bottom, co->caller_size);
#endif
#if defined (__x86_64__)
  void *dead;
  sym_co_swap (&dead, co->caller_sp);
#else
  setcontext (&co->caller);
#endif
  /* never resumed */
}

int
sym_co_init (sym_co *co, void *stack, size_t size, void (*fn) (void *),
             void *arg)
{
  memset (co, 0, sizeof *co);
#if defined (CO_VALGRIND)
  /* a stack used before (by a member that has ended) is new again: not
     the dead space below an old stack pointer */
  VALGRIND_MAKE_MEM_UNDEFINED (stack, size);
  co->vg_id = VALGRIND_STACK_REGISTER (stack, (char *) stack + size);
#endif
  co->stack = stack;
  co->size = size;
  co->fn = fn;
  co->arg = arg;
#if defined (__x86_64__)
  /* the frame sym_co_swap pops: the control words, six registers (0: rbp
     ends the chain of frames), and co_first as the address it returns
     to; rsp is then 8 below a multiple of 16, as after a call */
  uintptr_t top = ((uintptr_t) stack + size) & ~(uintptr_t) 15;
  uint64_t *sp = (uint64_t *) (top - 72);
  unsigned int mxcsr;
  unsigned short fcw;
  __asm__ volatile ("stmxcsr %0" : "=m" (mxcsr));
  __asm__ volatile ("fnstcw %0" : "=m" (fcw));
  memset (sp, 0, 72);
  memcpy (sp, &mxcsr, 4);
  memcpy ((char *) sp + 4, &fcw, 2);
  sp[7] = (uint64_t) (uintptr_t) co_first;
  co->sp = sp;
#else
  if (getcontext (&co->self))
    return -1;
  co->self.uc_stack.ss_sp = stack;
  co->self.uc_stack.ss_size = size;
  co->self.uc_link = NULL;
  makecontext (&co->self, co_first, 0);
#endif
  return 0;
}

void
sym_co_resume (sym_co *co)
{
  for (;;)
    {
#if CO_ASAN
      void *fake = NULL;
      __sanitizer_start_switch_fiber (&fake, co->stack, co->size);
#endif
      co_starting = co;
      co_current = co;
#if defined (__x86_64__)
      sym_co_swap (&co->caller_sp, co->sp);
#else
      swapcontext (&co->caller, &co->self);
#endif
      co_current = NULL;
#if CO_ASAN
      __sanitizer_finish_switch_fiber (fake, NULL, NULL);
#endif
      /* a call co wants made from here (sym_outside), then on with co */
      if (! co->out_fn)
        return;
      void (*fn) (void *) = co->out_fn;
      co->out_fn = NULL;
      fn (co->out_arg);
    }
}

void
sym_outside (void (*fn) (void *), void *arg)
{
  sym_co *co = co_current;
  if (! co)
    {
      fn (arg);
      return;
    }
  co->out_fn = fn;
  co->out_arg = arg;
  sym_co_yield (co);
}

void
sym_co_yield (sym_co *co)
{
#if CO_ASAN
  __sanitizer_start_switch_fiber (&co->fake, co->caller_bottom,
                                  co->caller_size);
#endif
#if defined (__x86_64__)
  sym_co_swap (&co->sp, co->caller_sp);
#else
  swapcontext (&co->self, &co->caller);
#endif
#if CO_ASAN
  co_asan_enter (co);
#endif
}

void
sym_co_release (sym_co *co)
{
#if defined (CO_VALGRIND)
  VALGRIND_STACK_DEREGISTER (co->vg_id);
#endif
  co->stack = NULL;
}
