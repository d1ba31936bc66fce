#!/bin/sh
# make deb: the Debian package whirl_VERSION-REVISION_ARCH.deb in BUILD/, for users who do not
# build: the program, libwhirl (shared and static), its headers, whirl.pc, the manual page, the
# scenes, plot scripts and example data (/usr/share/whirl), as `make install PREFIX=/usr` stages
# them (DESTDIR), built apart in BUILD/deb with Debian's hardening flags (dpkg-buildflags) and
# without MPI (Open MPI would be a runtime dependency of every user's program), stripped. The
# package depends on the runtime libraries only, as dpkg-shlibdeps finds them in the binaries;
# gnuplot and ffmpeg (pictures) are recommended. Then lintian, when installed, checks it.
# Variables from the Makefile: BUILD, VERSION, MAKE; DEB_REVISION (default 1), DEB_MAINTAINER.
set -e
: "${BUILD:?}" "${VERSION:?}"
make=${MAKE:-make}
revision=${DEB_REVISION:-1}
for tool in dpkg-deb dpkg-shlibdeps dpkg-architecture dpkg-buildflags; do
  command -v $tool >/dev/null || { echo "make deb: needs $tool (apt-get install dpkg-dev)" >&2; exit 1; }
done
arch=$(dpkg-architecture -qDEB_HOST_ARCH)
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
# the maintainer: DEB_MAINTAINER, else the author of the last commit
maintainer=${DEB_MAINTAINER:-$(git log -1 --format='%an <%ae>' 2>/dev/null || true)}
[ -n "$maintainer" ] || { echo "make deb: set DEB_MAINTAINER='Name <address>'" >&2; exit 1; }
# the date of the last commit (the same package from the same tree), else now
stamp=$(git log -1 --format=%ct 2>/dev/null || date +%s)
export SOURCE_DATE_EPOCH="$stamp"

work=$BUILD/deb
stage=$work/stage
out=$BUILD/whirl_${VERSION}-${revision}_$arch.deb
rm -rf "$stage" "$work/shlibdeps"
mkdir -p "$stage/DEBIAN"

# build and stage (hardened: fortify, stack protector, relro and bindnow)
export DEB_BUILD_MAINT_OPTIONS=hardening=+all
$make --no-print-directory -s BUILD="$work" MPI=0 PREFIX=/usr LIBDIR="/usr/lib/$multiarch" \
  CFLAGS="$(dpkg-buildflags --get CFLAGS)" XCFLAGS="$(dpkg-buildflags --get CPPFLAGS)" \
  LDFLAGS="$(dpkg-buildflags --get LDFLAGS)" DESTDIR="$(cd "$stage" && pwd)" install >/dev/null
lib=$stage/usr/lib/$multiarch
strip --strip-unneeded --remove-section=.comment --remove-section=.note \
  "$stage/usr/bin/whirl" "$lib/libwhirl.so.$VERSION"
strip --strip-debug --remove-section=.comment --enable-deterministic-archives "$lib/libwhirl.a"
gzip -9n "$stage/usr/share/man/man1/whirl.1"

# the documentation: copyright (machine-readable), the Debian changelog, the project's changelog
doc=$stage/usr/share/doc/whirl
mkdir -p "$doc"
# the years of the history (first and last commit)
first=$(git log --reverse --format=%ad --date=format:%Y 2>/dev/null | head -1)
last=$(date -u -d "@$stamp" +%Y)
years=${first:-$last}
[ "$years" = "$last" ] || years=$years-$last
cat >"$doc/copyright" <<EOF
Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/
Upstream-Name: whirl
Source: the whirl source tree (this package is built from it by make deb)

Files: *
Copyright: $years the whirl authors
License: GPL-3+

License: GPL-3+
 This program is free software: you can redistribute it and/or modify it under
 the terms of the GNU General Public License as published by the Free Software
 Foundation, either version 3 of the License, or (at your option) any later
 version.
 .
 This program is distributed in the hope that it will be useful, but WITHOUT
 ANY WARRANTY; without even the implied warranty of MERCHANTABILITY or FITNESS
 FOR A PARTICULAR PURPOSE. See the GNU General Public License for more details.
 .
 On Debian systems, the complete text of the GNU General Public License
 version 3 can be found in "/usr/share/common-licenses/GPL-3".
EOF
{
  echo "whirl ($VERSION-$revision) unstable; urgency=medium"
  echo
  echo "  * whirl $VERSION, packaged from the source tree by make deb (the changes of"
  echo "    the release: /usr/share/doc/whirl/changelog.gz)."
  echo
  echo " -- $maintainer  $(date -u -R -d "@$stamp")"
} | gzip -9n >"$doc/changelog.Debian.gz"
gzip -9n <CHANGELOG.md >"$doc/changelog.gz"
# a single package for users who do not build: the library's files are in it too (lintian
# expects a library in its own package named after its SONAME, libwhirl2, and the headers in a
# -dev package; one package is what this is for)
mkdir -p "$stage/usr/share/lintian/overrides"
cat >"$stage/usr/share/lintian/overrides/whirl" <<EOF
# one package holds the program, libwhirl and the files to build with it (make deb)
whirl: package-name-doesnt-match-sonames libwhirl2
whirl: link-to-shared-library-in-wrong-package *
# built from the source tree for users, not uploaded to Debian: no ITP bug to close
whirl: initial-upload-closes-no-bugs *
EOF
find "$stage" -type d -exec chmod 755 {} +
find "$stage" -type f -exec chmod 644 {} +
chmod 755 "$stage/usr/bin/whirl"

# runtime dependencies: those of the binaries, from the libraries' packages
mkdir -p "$work/shlibdeps/debian"
printf 'Source: whirl\n\nPackage: whirl\nArchitecture: any\n' >"$work/shlibdeps/debian/control"
depends=$(cd "$work/shlibdeps" && dpkg-shlibdeps -O -e"$(cd ../stage && pwd)/usr/bin/whirl" \
  -e"$(cd ../stage && pwd)/usr/lib/$multiarch/libwhirl.so.$VERSION" 2>/dev/null |
  sed -n 's/^shlibs:Depends=//p')
[ -n "$depends" ] || { echo "make deb: dpkg-shlibdeps found no dependencies" >&2; exit 1; }

# the control files: control, md5sums, shlibs (libwhirl.so.2 for other packages), the loader's
# cache refreshed on install and removal (ldconfig trigger)
size=$(du -sk --exclude=DEBIAN "$stage" | cut -f1)
cat >"$stage/DEBIAN/control" <<EOF
Package: whirl
Version: $VERSION-$revision
Architecture: $arch
Maintainer: $maintainer
Installed-Size: $size
Depends: $depends
Recommends: gnuplot-nox | gnuplot, ffmpeg
Section: science
Priority: optional
Description: steady shapes, dynamics and stability of a spinning chain
 whirl computes the steady shapes of a chain spun about the vertical axis (the
 continuous chain and chains of N links), their branches against the rotation
 rate, their linear stability and windows of instability, and runs the chain
 in time from scene files; with figures and movies of its results (gnuplot,
 ffmpeg) and a 3D viewer in one HTML page.
 .
 This package holds the whirl program and its manual page, the libwhirl C
 library (shared and static) with its headers and pkg-config file, and the
 example scenes, plot scripts and data in /usr/share/whirl.
EOF
(cd "$stage" && find . -path ./DEBIAN -prune -o -type f -print | sed 's|^\./||' | sort |
  xargs md5sum) >"$stage/DEBIAN/md5sums"
echo "libwhirl ${VERSION%%.*} whirl (>= $VERSION)" >"$stage/DEBIAN/shlibs"
# the exported symbols, each from this version on (dpkg-gensymbols), and the package whose
# headers build against them
(cd "$work/shlibdeps" && dpkg-gensymbols -q -pwhirl -v"$VERSION" -P"$(cd ../stage && pwd)" \
  -e"$(cd ../stage && pwd)/usr/lib/$multiarch/libwhirl.so.$VERSION" -O"$(cd ../stage && pwd)/DEBIAN/symbols")
sed -i '1a\
* Build-Depends-Package: whirl' "$stage/DEBIAN/symbols"
echo "activate-noawait ldconfig" >"$stage/DEBIAN/triggers"
chmod 644 "$stage/DEBIAN/"*

dpkg-deb --root-owner-group -Zxz --build "$stage" "$out" >/dev/null
echo "make deb: $out ($(du -k "$out" | cut -f1) kB)"
echo "  Depends: $depends"
if command -v lintian >/dev/null; then
  echo "lintian:"
  lintian -I --show-overrides "$out" | sed 's/^/  /'
  echo "  (lintian done)"
else
  echo "lintian: not installed (apt-get install lintian)"
fi
