#!/bin/sh
# The toolchain of the web build (make web): Debian's emscripten, and GSL compiled to WebAssembly
# from Debian's own source package, built once per machine into a cache keyed by its version.
#
#   sh scripts/web-deps.sh        prints the GSL prefix (PREFIX/include, PREFIX/lib/libgsl.a)
#
# Everything comes from Debian, pinned: the packages by version, the source package checked by
# apt against its signed .dsc, and the upstream tarball again here by its sha256. Installing
# needs root (apt-get); without it the script names the command and fails. Idempotent: a cache
# whose stamp names the same version and checksum is used as it is.
#
# The emscripten of bookworm (3.1.6) on a current Node: its configure probes run the compiled
# programs under Node, whose experimental fetch breaks the old runtime
# (NODE_OPTIONS=--no-experimental-fetch), and its optimiser loads acorn, which Debian ships in its
# own folder of Node modules (node-acorn, NODE_PATH=/usr/share/nodejs).
set -eu

EMSCRIPTEN_VERSION=3.1.6~dfsg-5
GSL_SOURCE_VERSION=2.7.1+dfsg-5+deb12u1
GSL_ORIG=gsl_2.7.1+dfsg.orig.tar.gz
GSL_ORIG_SHA256=e560d6b9c6e254e46769bbb03583c00ecafbdd51b062c55db23b3b9612868567
GSL_DEBIAN=gsl_2.7.1+dfsg-5+deb12u1.debian.tar.xz
GSL_DEBIAN_SHA256=c48c5cd287b15844092e9c392c12b9bc385f0ab86f157184de5cc23c8963652b
# NLopt and inih are not built: only src/optimize and src/studies use them, and the page needs
# neither (the Makefile leaves them out of the web build).
# The cache: /var/cache/whirl-web for root, else the user's cache folder
if [ "$(id -u)" = 0 ]; then default_cache=/var/cache/whirl-web
else default_cache=${XDG_CACHE_HOME:-$HOME/.cache}/whirl-web; fi
CACHE=${WHIRL_WEB_CACHE:-$default_cache}
PREFIX=$CACHE/gsl-$GSL_SOURCE_VERSION

say() { echo "web-deps: $*" >&2; }
die() { say "$*"; exit 1; }

export NODE_OPTIONS=--no-experimental-fetch
export NODE_PATH=/usr/share/nodejs

stamp="$GSL_SOURCE_VERSION $GSL_ORIG_SHA256 emscripten $EMSCRIPTEN_VERSION"
if [ -f "$PREFIX/stamp" ] && [ "$(cat "$PREFIX/stamp")" = "$stamp" ] && [ -f "$PREFIX/lib/libgsl.a" ] &&
  command -v emcc >/dev/null 2>&1; then
  echo "$PREFIX"
  exit 0
fi

# ---- the packages: emscripten (with clang, lld, binaryen) and acorn for its optimiser
installed() { dpkg-query -W -f '${Version}' "$1" 2>/dev/null; }
need=""
[ "$(installed emscripten)" = "$EMSCRIPTEN_VERSION" ] || need="$need emscripten=$EMSCRIPTEN_VERSION"
[ -n "$(installed node-acorn)" ] || need="$need node-acorn"
[ -n "$(installed dpkg-dev)" ] || need="$need dpkg-dev"
[ -n "$(installed xz-utils)" ] || need="$need xz-utils"
if [ -n "$need" ]; then
  [ "$(id -u)" = 0 ] || die "missing:$need; as root: apt-get install$need"
  say "installing$need"
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q $need >&2
fi

# ---- the source package: a deb-src line for the suites of the binary packages
if ! grep -rqs '^Types:.*deb-src\|^deb-src ' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  [ "$(id -u)" = 0 ] || die "no deb-src line in /etc/apt/sources.list.d/; as root add one for bookworm"
  say "adding /etc/apt/sources.list.d/whirl-web-src.sources (deb-src of bookworm)"
  cat >/etc/apt/sources.list.d/whirl-web-src.sources <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb-src
URIs: http://deb.debian.org/debian-security
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
  apt-get update -q >&2
fi

mkdir -p "$CACHE/src"
cd "$CACHE/src"
if [ ! -f "$GSL_ORIG" ] || [ ! -d "gsl-2.7.1+dfsg" ]; then
  say "apt-get source gsl=$GSL_SOURCE_VERSION"
  rm -rf gsl-2.7.1+dfsg
  apt-get source -q "gsl=$GSL_SOURCE_VERSION" >&2 || {
    apt-get update -q >&2
    apt-get source -q "gsl=$GSL_SOURCE_VERSION" >&2
  }
fi
printf '%s  %s\n%s  %s\n' "$GSL_ORIG_SHA256" "$GSL_ORIG" "$GSL_DEBIAN_SHA256" "$GSL_DEBIAN" |
  sha256sum -c --quiet - >&2 || die "$CACHE/src: the sha256 of $GSL_ORIG or $GSL_DEBIAN differs from the pinned one"

# ---- GSL for WebAssembly: static, no shared library, installed under PREFIX
build=$CACHE/build-gsl-$GSL_SOURCE_VERSION
rm -rf "$build" "$PREFIX"
cp -a gsl-2.7.1+dfsg "$build"
cd "$build"
say "building GSL for WebAssembly in $build (a few minutes)"
nice emconfigure ./configure --disable-shared --enable-static --prefix="$PREFIX" CFLAGS=-O2 >configure.log 2>&1 ||
  die "configure failed: $build/configure.log"
# Debian's source (+dfsg) has no manual sources: the folder of the manual is skipped
printf 'all:\ninstall:\n.PHONY: all install\n' >doc/Makefile
nice emmake make -j2 >make.log 2>&1 || die "make failed: $build/make.log"
nice emmake make install >install.log 2>&1 || die "make install failed: $build/install.log"
echo "$stamp" >"$PREFIX/stamp"
cd "$CACHE" && rm -rf "$build"
say "GSL for WebAssembly in $PREFIX"
echo "$PREFIX"
