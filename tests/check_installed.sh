#!/bin/sh
# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.
# check_installed.sh -- the package as someone who has only its tarball
# gets it (make check-installed; about 10 s).
#
#   tests/check_installed.sh [OCTAVE]
#
# 1. make dist: symplectic-<version>.tar.gz at the top of the tree.
# 2. A non-root user with an empty home directory: this user when not
#    root; as root, the user `nobody` (SYM_CHECK_USER=name for another),
#    through runuser (or setpriv), with a clean environment (env -i) and
#    HOME in a temporary directory.  Octave then reads nothing of the
#    caller's configuration or packages.
# 3. As that user, in one Octave session: pkg install of the tarball into
#    the user's own prefix, split as a global install is (prefix
#    $HOME/octave/share, archprefix $HOME/octave/lib), so that the
#    architecture-dependent files can be told from the rest.
# 4. In a new session: pkg load symplectic; pkg test symplectic (no
#    failure, at least one test); lookfor symplectic (lists odeSE, odeSV,
#    odeSPVI); where odeSPVI and __odeSPVI__ resolve.
# 5. In a new session, with no display and stdin from /dev/null: the
#    demo of each function (odeSE, odeSV, odeSPVI, symplecticset,
#    symdeval) runs and, when a graphics toolkit can print, writes its
#    PNG.
# 6. In a new session: tests/test_examples.m of the unpacked tarball on
#    the installed package: every example of README.md, of the installed
#    user guide and of the help texts runs.
# 7. Files: every .mex in the architecture directory (getarch () under
#    archprefix, as pkg list gives it), none under the package directory
#    (the arch-independent tree), no object files anywhere; the user
#    guide in the package's doc/, where the README says it is.
#
# Prints a one-line summary last; exits non-zero on any failure.  Logs of
# every step: build/check-installed/ (kept after a failure).

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
OCTAVE=${1:-octave-cli}
start=$(date +%s)
logdir=$root/build/check-installed
rm -rf "$logdir"
mkdir -p "$logdir" || exit 1

tmp=
cleanup () { [ -n "$tmp" ] && rm -rf "$tmp"; }
trap cleanup EXIT
trap 'exit 130' INT TERM

fail () {
  echo "check-installed: FAIL: $*"
  exit 1
}
# show_log FILE: the end of a step's log (Octave's exit-time
# "error: ignoring const execution_exception&" line is noise, dropped)
show_log () {
  grep -v "ignoring const execution_exception" "$1" | tail -n 40
}

octave=$(command -v "$OCTAVE") || fail "$OCTAVE not found (make deps)"

# 1. the tarball
name=$(sed -n 's/^Name:[[:space:]]*//p' "$root/DESCRIPTION")
version=$(sed -n 's/^Version:[[:space:]]*//p' "$root/DESCRIPTION")
tarball=$name-$version.tar.gz
echo "check-installed: make dist"
make -C "$root" --no-print-directory dist > "$logdir/dist.log" 2>&1 \
  || { show_log "$logdir/dist.log"; fail "make dist"; }
[ -f "$root/$tarball" ] || fail "make dist made no $tarball"

# 2. the user and its home
tmp=$(mktemp -d) || exit 1
home=$tmp/home
mkdir "$home" && cp "$root/$tarball" "$home/" || exit 1
if [ "$(id -u)" -eq 0 ]; then
  user=${SYM_CHECK_USER:-nobody}
  uid=$(id -u "$user" 2>/dev/null) || fail "no user $user"
  [ "$uid" -ne 0 ] || fail "user $user is root"
  group=$(id -gn "$user")
  chmod 711 "$tmp"            # the user may pass through, not list
  chown -R "$user:$group" "$home"
  if command -v runuser > /dev/null 2>&1; then
    as_user () { runuser -u "$user" -- "$@"; }
  elif command -v setpriv > /dev/null 2>&1; then
    as_user () { setpriv --reuid="$user" --regid="$group" --init-groups -- "$@"; }
  else
    fail "running as root, and neither runuser nor setpriv to become $user"
  fi
else
  user=$(id -un)
  as_user () { "$@"; }
fi
# run_octave LOG CODE: CODE in a clean octave-cli as the user, in $home
run_octave () {
  log=$1
  shift
  (cd "$home" && as_user env -i HOME="$home" PATH="$PATH" LANG=C.UTF-8 \
     OPENBLAS_NUM_THREADS=1 "$octave" --norc --quiet --no-gui --no-history \
     --eval "$1") > "$log" 2>&1
}
pkgdirs="'$home/octave/share', '$home/octave/lib'"

# 3. pkg install
echo "check-installed: pkg install $tarball as $user (HOME=$home)"
run_octave "$logdir/install.log" "
  pkg ('prefix', $pkgdirs);
  pkg ('install', '$home/$tarball');
  printf ('INSTALLED\n');" \
  && grep -q "^INSTALLED" "$logdir/install.log" \
  || { show_log "$logdir/install.log"; fail "pkg install"; }

# 4. pkg test, lookfor, where the functions resolve
echo "check-installed: pkg load $name; pkg test $name"
run_octave "$logdir/test.log" "
  pkg load $name;
  info = pkg ('list', '$name');
  ## getarch () of pkg/private
  arch = [__octave_config_info__('canonical_host_type'), '-', ...
          __octave_config_info__('api_version')];
  printf ('DIR=%s\nARCHPREFIX=%s\nARCHDIR=%s\n', info{1}.dir,
          info{1}.archprefix, fullfile (info{1}.archprefix, arch));
  printf ('WHICH=%s\nWHICH=%s\n', which ('odeSPVI'), which ('__odeSPVI__'));
  printf ('UID=%d\n', getuid ());
  pkg test $name;
  lookfor $name;
  printf ('TESTED\n');"
show_test () { show_log "$logdir/test.log"; }
grep -q "^TESTED" "$logdir/test.log" || { show_test; fail "pkg load/test"; }
npass=$(sed -n 's/^ *PASS  *\([0-9][0-9]*\)$/\1/p' "$logdir/test.log" | tail -n 1)
nfail=$(sed -n 's/^ *FAIL  *\([0-9][0-9]*\)$/\1/p' "$logdir/test.log" | tail -n 1)
if [ -z "$npass" ] || [ -z "$nfail" ] || [ "$npass" -eq 0 ] || [ "$nfail" -ne 0 ]; then
  show_test
  fail "pkg test $name: ${npass:-no} passed, ${nfail:-no} failed"
fi
for f in odeSE odeSV odeSPVI; do
  grep -q "^$f  " "$logdir/test.log" || { show_test; fail "lookfor $name does not list $f"; }
done
[ "$(sed -n 's/^UID=//p' "$logdir/test.log")" = "$(id -u "$user")" ] \
  && [ "$(id -u "$user")" -ne 0 ] || fail "Octave did not run as $user"
dir=$(sed -n 's/^DIR=//p' "$logdir/test.log")
archprefix=$(sed -n 's/^ARCHPREFIX=//p' "$logdir/test.log")
[ -d "$dir" ] && [ -d "$archprefix" ] || { show_test; fail "pkg list: no dir or archprefix"; }
grep -q "^WHICH=$dir/odeSPVI.m$" "$logdir/test.log" \
  && grep -q "^WHICH=$archprefix/.*/__odeSPVI__.mex$" "$logdir/test.log" \
  || { grep "^WHICH" "$logdir/test.log"; fail "odeSPVI is not $dir/odeSPVI.m calling a .mex under $archprefix"; }

# 5. the demos, with no terminal and no display (demo catches an
# example's error and prints "NAME example N: failed"; a second demo in
# a file would make it prompt, which fails with stdin from /dev/null)
demos="odeSE odeSV odeSPVI symplecticset symdeval"
echo "check-installed: demo $demos (stdin /dev/null, no display)"
run_octave "$logdir/demo.log" "
  pkg load $name;
  for f = strsplit ('$demos')
    demo (f{1});
  endfor
  printf ('TOOLKITS=%d\nDEMOS DONE\n', numel (available_graphics_toolkits ()));" \
  < /dev/null
nrun=0
for f in $demos; do
  grep -q "^$f example 1:$" "$logdir/demo.log" || { show_log "$logdir/demo.log"; fail "demo $f did not run"; }
  nrun=$((nrun + 1))
done
if ! grep -q "^DEMOS DONE" "$logdir/demo.log" \
   || grep -q "example [0-9]*: failed" "$logdir/demo.log"; then
  show_log "$logdir/demo.log"
  fail "the demos ($demos)"
fi
npng=$(find "$home" -maxdepth 1 -name '*-demo.png' | wc -l)
if [ "$(sed -n 's/^TOOLKITS=//p' "$logdir/demo.log")" != 0 ] && [ "$npng" -ne "$nrun" ]; then
  show_log "$logdir/demo.log"
  fail "$npng PNG files from $nrun demos with no display"
fi

# 6. the examples of README, the installed guide and the help texts, by
# the source tree's test, on the installed package
echo "check-installed: tests/test_examples.m on the installed package"
mkdir "$tmp/src" && tar -C "$tmp/src" -xzf "$root/$tarball" && chmod -R a+rX "$tmp/src" \
  || fail "unpacking $tarball"
srcdir=$tmp/src/$name-$version
run_octave "$logdir/examples.log" "
  pkg load $name;
  addpath ('$srcdir/tests');
  [n, m] = test ('$srcdir/tests/test_examples.m', 'quiet', stdout);
  printf ('EXAMPLES %d %d\n', n, m);"
nex=$(sed -n 's/^EXAMPLES \([0-9]*\) \([0-9]*\)$/\1 \2/p' "$logdir/examples.log")
set -- $nex
if [ -z "$nex" ] || [ "$1" -ne "$2" ] || [ "$2" -eq 0 ]; then
  show_log "$logdir/examples.log"
  fail "tests/test_examples.m on the installed package: ${1:-no} of ${2:-no} passed"
fi
nexamples=$1

# 7. the files
nmex_arch=$(find "$archprefix" -name '*.mex' | wc -l)
mex_indep=$(find "$dir" -name '*.mex')
objs=$(find "$dir" "$archprefix" -name '*.o')
[ -z "$mex_indep" ] || fail "MEX files in the arch-independent tree: $mex_indep"
[ -z "$objs" ] || fail "object files installed: $objs"
[ -f "$dir/doc/user-guide.md" ] || fail "no doc/user-guide.md in $dir"
nsrc=$(tar -tzf "$root/$tarball" | grep -c "/src/__[A-Za-z0-9]*__\.c$")
[ "$nmex_arch" -eq "$nsrc" ] \
  || fail "$nmex_arch .mex files under $archprefix, expected $nsrc"
[ "$(find "$archprefix" -name '*.mex' -exec dirname {} \; | sort -u)" \
  = "$(sed -n 's/^ARCHDIR=//p' "$logdir/test.log")" ] \
  || fail "the .mex files are not all in the architecture directory"

secs=$(($(date +%s) - start))
echo "check-installed: passed: $tarball installed by $user (not root): pkg test $npass passed, 0 failed; $nrun demos headless ($npng PNG); test_examples $nexamples passed; $nmex_arch .mex in the arch dir, none beside the m-files ($secs s)"
