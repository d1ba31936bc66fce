#!/bin/sh
# Installs or uninstalls whirl: install.sh install|uninstall, with the variables the Makefile
# passes: BUILD (the built files), VERSION, MAJOR, DESTDIR (staging root, may be empty), PREFIX,
# BINDIR, LIBDIR, INCLUDEDIR, MANDIR, PKGCONFIGDIR, DATADIR (the scenes, plot scripts and example
# data, which the program's --help names), PROGRAM and MANPAGE (the program and its manual page
# built for DATADIR; default BUILD/whirl, BUILD/whirl.1). Before installing anything every target
# directory is created and written to once, so an unwritable prefix fails with one clear error
# and leaves nothing half installed.
set -e
action=$1
: "${BUILD:?}" "${VERSION:?}" "${MAJOR:?}" "${PREFIX:?}" "${BINDIR:?}" "${LIBDIR:?}"
: "${INCLUDEDIR:?}" "${MANDIR:?}" "${PKGCONFIGDIR:?}" "${DATADIR:?}"
case $PREFIX in /*) ;; *) echo "make $action: PREFIX must be an absolute path (got '$PREFIX')" >&2; exit 1 ;; esac
d=${DESTDIR}
real=libwhirl.so.$VERSION
headers=$(cd include && ls whirl.h whirl/*.h)
shared=$(ls data/scenes/*.ini plots/*.gp data/fit_example.csv | sed 's|^data/||')

if [ "$action" = uninstall ]; then
  rm -f "$d$BINDIR/whirl" "$d$LIBDIR/libwhirl.a" "$d$LIBDIR/$real" "$d$LIBDIR/libwhirl.so.$MAJOR" \
        "$d$LIBDIR/libwhirl.so" "$d$PKGCONFIGDIR/whirl.pc" "$d$MANDIR/man1/whirl.1"
  for h in $headers; do rm -f "$d$INCLUDEDIR/$h"; done
  rmdir "$d$INCLUDEDIR/whirl" 2>/dev/null || true
  for f in $shared; do rm -f "$d$DATADIR/$f"; done
  rmdir "$d$DATADIR/scenes" "$d$DATADIR/plots" "$d$DATADIR" 2>/dev/null || true
  echo "whirl: uninstalled from $d$PREFIX"
  exit 0
fi

for dir in "$d$BINDIR" "$d$LIBDIR" "$d$PKGCONFIGDIR" "$d$INCLUDEDIR/whirl" "$d$MANDIR/man1" \
           "$d$DATADIR/scenes" "$d$DATADIR/plots"; do
  probe="$dir/.whirl-install.$$"
  if ! { mkdir -p "$dir" && : >"$probe"; } 2>/dev/null; then
    echo "make install: cannot write to $dir (choose a writable PREFIX=... or DESTDIR=..., or install as root)" >&2
    exit 1
  fi
  rm -f "$probe"
done

install -m 755 "${PROGRAM:-$BUILD/whirl}" "$d$BINDIR/whirl"
install -m 644 "$BUILD/libwhirl.a" "$d$LIBDIR/libwhirl.a"
install -m 755 "$BUILD/$real" "$d$LIBDIR/$real"
ln -sf "$real" "$d$LIBDIR/libwhirl.so.$MAJOR"
ln -sf "libwhirl.so.$MAJOR" "$d$LIBDIR/libwhirl.so"
for h in $headers; do install -m 644 "include/$h" "$d$INCLUDEDIR/$h"; done
install -m 644 "${MANPAGE:-$BUILD/whirl.1}" "$d$MANDIR/man1/whirl.1"
for f in $shared; do
  case $f in plots/*) src=$f ;; *) src=data/$f ;; esac
  install -m 644 "$src" "$d$DATADIR/$f"
done
sed -e "s|@PREFIX@|$PREFIX|" -e "s|@LIBDIR@|$LIBDIR|" -e "s|@INCLUDEDIR@|$INCLUDEDIR|" \
    -e "s|@VERSION@|$VERSION|" whirl.pc.in >"$d$PKGCONFIGDIR/whirl.pc"
chmod 644 "$d$PKGCONFIGDIR/whirl.pc"
echo "whirl $VERSION: installed in $d$PREFIX"
