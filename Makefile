# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

# Makefile -- developer entry point of the symplectic Octave package.
#
#   make [all]          build the MEX files (no root, no network, no valgrind)
#   make deps           install the missing Debian packages (Octave, its
#                       headers, LAPACK/BLAS, KLU, the parallel package;
#                       tools/install-deps.sh)
#   make deps-memory    deps, and valgrind for check-memory and valgrind
#   make demo           deps and all, then run tools/demo.m
#   make check          deps and all, then the whole test suite (C + Octave)
#   make check-quick    all, then the C tests and the Octave tests of the
#                       main paths (QUICK_TESTS below; ~2 min on 2 cores)
#   make check-blas     all, then the regression and the solvers' tests under
#                       OpenBLAS core types, the reference BLAS/LAPACK and
#                       libm without FMA (tools/check-blas.sh, ~2 min);
#                       FULL=1: the whole Octave suite under each (~10 min each)
#   make valgrind       deps-memory, then the C tests under valgrind
#   make check-memory   deps-memory and all, then the MEX functions under
#                       valgrind (tests/check_memory.sh, ~90 s)
#   make dist           symplectic-<version>.tar.gz, the tarball pkg install takes
#   make install        dist, then pkg install it into Octave
#   make check-installed  pkg install the tarball as a non-root user, then
#                       pkg test and demo odeSPVI (tests/check_installed.sh)
#   make bench          deps and all, then bench/run_benchmarks.m (RESULTS.md),
#                       bench/run_methods.m (METHODS.md, methods-*.png),
#                       bench/run_verletform.m (VERLETFORM.md),
#                       bench/run_reversible.m (REVERSIBLE.md, its PNG),
#                       bench/run_large.m (LARGE.md),
#                       bench/run_ensemble.m (ENSEMBLE.md) and bench-core
#   make bench-core     bench/core_cost.c, the core without Octave, and
#                       bench/gauss_loop.c, a plain Gauss loop (CORE.md)
#   make bench-gauss    bench/gauss_loop.c alone, to standard output
#   make clean
#
# src/Makefile builds the compiled gateways __odeSE__.mex etc. in src/;
# the m-files of inst/ (help, tests, the front ends odeSE etc.) call them.
# Without installing, Octave needs both on its path: DEVPATH.

# bash for pipefail: `make check` tees the output of its parts.
SHELL := /bin/bash -o pipefail

OCTAVE    ?= octave-cli
MKOCTFILE ?= mkoctfile
export MKOCTFILE

# --norc: no user or site startup files, so runs are reproducible.
OCTAVE_RUN := $(OCTAVE) --norc --quiet --no-gui
# Octave ignores SIGTERM while it waits at exit: KILL a minute later.
TEST_TIMEOUT := $(if $(shell command -v timeout 2>/dev/null),timeout -k 60 2400)

PACKAGE  := $(shell sed -n 's/^Name:[[:space:]]*//p' DESCRIPTION)
VERSION  := $(shell sed -n 's/^Version:[[:space:]]*//p' DESCRIPTION)
DISTNAME := $(PACKAGE)-$(VERSION)
TARBALL  := $(DISTNAME).tar.gz

# The development tree's m-files and MEX files, for Octave's --path and
# addpath (both split a path at ':').
DEVPATH := $(CURDIR)/inst:$(CURDIR)/src

# What the tarball holds: what pkg install needs (DESCRIPTION, INDEX,
# COPYING, NEWS, inst/, src/ with its Makefile; doc/ is installed with the
# package), plus what the README's make commands need in the unpacked
# tarball: this Makefile, tools/, tests/, bench/ and the documents.
DIST_FILES := DESCRIPTION INDEX COPYING NEWS README.md ARCHITECTURE.md \
              Makefile inst src doc tests tools bench

# Build only: `make -C src` alone (what pkg runs) would also remove the
# objects after linking; `mex` keeps them, for quick rebuilds.
all:
	$(MAKE) -C src mex

deps:
	sh tools/install-deps.sh

deps-memory:
	sh tools/install-deps.sh memory

# deps, then the build (in this order, also under make -j).
setup: deps
	$(MAKE) --no-print-directory all

demo: setup
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH)" tools/demo.m

# Runs the C and the Octave tests side by side (each is one process at a
# time, so two cores take both), shows the Octave ones as they run and the
# C ones' log after, then prints the totals as its last line, "N passed,
# M failed", and fails if any test failed.  A part that printed no
# summary (e.g. it did not build) counts as one failure.
check: setup
	@mkdir -p build; status=0; \
	{ $(MAKE) --no-print-directory check-c > build/check-c.log 2>&1; \
	  echo $$? > build/check-c.status; } & cpid=$$!; \
	$(MAKE) --no-print-directory check-octave 2>&1 | tee build/check-octave.log \
	  || status=1; \
	wait $$cpid; cat build/check-c.log; \
	[ "$$(cat build/check-c.status)" = 0 ] || status=1; \
	c=$$(sed -n 's/^C tests.*: \([0-9]* passed, [0-9]* failed\)$$/\1/p' build/check-c.log | tail -n 1); \
	o=$$(sed -n 's/^\([0-9]* passed, [0-9]* failed\)$$/\1/p' build/check-octave.log | tail -n 1); \
	echo "C tests:      $${c:-no summary (counted as 1 failure)}"; \
	echo "Octave tests: $${o:-no summary (counted as 1 failure)}"; \
	set -- $${c:-0 passed, 1 failed}; p=$$1; f=$$3; \
	set -- $${o:-0 passed, 1 failed}; p=$$((p + $$1)); f=$$((f + $$3)); \
	if [ $$f -ne 0 ]; then status=1; fi; \
	if [ $$status -ne 0 ] && [ $$f -eq 0 ]; then f=1; fi; \
	echo "$$p passed, $$f failed"; \
	exit $$status

check-c:
	$(MAKE) -C tests/c check

# The Octave files of check-quick: each solver's fixed and adaptive paths,
# the options and bad input; run_tests.m takes them from SYMPLECTIC_TESTS.
QUICK_TESTS = inst/odeSE.m inst/odeSV.m inst/odeSPVI.m inst/symplecticset.m \
  tests/test_bad_input.m tests/test_se_sv.m tests/test_spvi.m

check-quick: all
	$(MAKE) --no-print-directory check-c
	SYMPLECTIC_TESTS="$(QUICK_TESTS)" \
	  $(OCTAVE_RUN) --eval 'addpath ("$(CURDIR)/tests"); exit (run_tests ())'

# tests/run_tests.m prints "N passed, M failed" last and returns the exit
# status (non-zero on any failure or when no test ran).
# A hung run (e.g. a process that never exits) fails after 40 min.
check-octave: all
	$(TEST_TIMEOUT) $(OCTAVE_RUN) --eval 'addpath ("$(CURDIR)/tests"); exit (run_tests ())'

check-blas: all
	@mkdir -p build
	bash tools/check-blas.sh "$(OCTAVE)" "$(DEVPATH)" $(if $(filter 1,$(FULL)),full,quick) \
	  2>&1 | tee build/check-blas.log

valgrind: deps-memory
	$(MAKE) -C tests/c valgrind

# Fails on memory errors (invalid reads/writes, uninitialised values) whose
# stack involves our code; Octave's own noise is reported, not failed.
check-memory: deps-memory
	$(MAKE) --no-print-directory all
	sh tests/check_memory.sh "$(DEVPATH)" "$(OCTAVE)"

bench: setup
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH)" bench/run_benchmarks.m
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH)" bench/run_methods.m
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH)" bench/run_verletform.m
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH):$(CURDIR)/bench" bench/run_reversible.m
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH):$(CURDIR)/bench" bench/run_large.m
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH):$(CURDIR)/bench" bench/run_ensemble.m
	$(MAKE) --no-print-directory bench-core
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH):$(CURDIR)/bench" bench/run_compiled.m
	$(OCTAVE) --norc --no-gui --path "$(DEVPATH):$(CURDIR)/bench" --eval tangent_cost

# The core alone, compiled as the gateways are (-O2) and linked with the
# LAPACK and BLAS Octave links.
CORE_SRC  := $(shell find src/core -name '*.c' | sort)
CORE_LIBS  = -lklu -lsuitesparseconfig \
             $(or $(shell $(MKOCTFILE) -p LAPACK_LIBS 2>/dev/null),-llapack) \
             $(or $(shell $(MKOCTFILE) -p BLAS_LIBS 2>/dev/null),-lblas) -lm
build/bench/core_cost: bench/core_cost.c bench/timing.h $(CORE_SRC) $(shell find src/core -name '*.h')
	@mkdir -p build/bench
	$(CC) -std=c99 -Wall -O2 -Isrc/core -o $@ bench/core_cost.c $(CORE_SRC) $(CORE_LIBS)

build/bench/gauss_loop: bench/gauss_loop.c bench/timing.h
	@mkdir -p build/bench
	$(CC) -std=c99 -Wall -O2 -o $@ bench/gauss_loop.c -lm

bench-core: deps build/bench/core_cost build/bench/gauss_loop
	build/bench/core_cost bench/CORE.md
	build/bench/gauss_loop bench/CORE.md

# The plain Gauss collocation loop alone, to standard output.
bench-gauss: build/bench/gauss_loop
	build/bench/gauss_loop

# Stage a clean copy (no build products) and pack it as DISTNAME/.  In a
# git checkout only the files git tracks are packed (as they are in the
# working tree), so no scratch or editor file of the tree gets in.
dist:
	rm -rf build/dist $(TARBALL)
	mkdir -p build/dist/$(DISTNAME)
	if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then \
	  git ls-files -z -- $(DIST_FILES) \
	    | xargs -0 cp --parents -t build/dist/$(DISTNAME)/; \
	else \
	  cp -R $(DIST_FILES) build/dist/$(DISTNAME)/; \
	fi
	cd build/dist/$(DISTNAME) && \
	  rm -rf tests/c/build src/obj && \
	  find . \( -name '*.o' -o -name '*.mex' -o -name '*.oct' -o -name '*.c-tst' \
	            -o -name '*.d' -o -name 'fntests.log' -o -name 'octave-workspace' \) \
	         -exec rm -f {} +
	tar -C build/dist --owner=0 --group=0 --numeric-owner \
	    -czf $(TARBALL) $(DISTNAME)
	rm -rf build/dist
	@echo "dist: $(TARBALL)"

# pkg install: global (/usr/share/octave/packages) when run as root, into
# ~/.local/share/octave otherwise; running it again replaces the copy.
install: dist
	$(OCTAVE_RUN) --eval 'pkg install "$(CURDIR)/$(TARBALL)"'
	@echo "installed; in Octave: pkg load $(PACKAGE)"

# make dist, then pkg install of the tarball as a non-root user into a
# throw-away prefix, pkg test and demo odeSPVI there (about 10 s).
check-installed:
	sh tests/check_installed.sh "$(OCTAVE)"

clean:
	$(MAKE) -C src clean
	$(MAKE) -C tests/c clean
	rm -rf build $(PACKAGE)-*.tar.gz fntests.log octave-workspace \
	       demo-energy.png bench/callback_cost.mex
	# MEX files that builds before 0.2.0 put in inst/ (they would shadow
	# the m-files there)
	rm -f inst/*.mex

.PHONY: all deps deps-memory setup demo check check-quick check-c check-octave check-blas valgrind \
        check-memory bench bench-core bench-gauss dist install check-installed clean
