#!/usr/bin/env bash
# Installation and the Debian package (issue 16):
#   tests/install/test_install.sh BUILD_DIR
# `cmake --install` into a temporary prefix puts both programs, the man pages, the docs, the
# desktop entry, the scene file type (shared-mime-info) and the icon where a Debian desktop finds
# them, and the installed programs run (phonglab-cli finds phonglab-bench beside it). `cpack -G
# DEB` makes a package whose contents are the same; as root (CI) it is installed with dpkg, run
# from /usr/bin, and removed, leaving nothing behind.
set -u
BUILD_DIR=$(cd "${1:?usage: test_install.sh BUILD_DIR}" && pwd)
failures=0
pass() { echo "  ok    $*"; }
fail() { echo "  FAIL  $*"; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@" >/dev/null 2>&1; then pass "$what"; else fail "$what"; fi; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

prefix=$work/prefix
cmake --install "$BUILD_DIR" --prefix "$prefix" >"$work/install.log" 2>&1
check "cmake --install succeeds" test $? = 0
for f in bin/phonglab bin/phonglab-cli bin/phonglab-bench share/man/man1/phonglab.1 share/man/man1/phonglab-cli.1 \
         share/applications/phonglab.desktop share/icons/hicolor/scalable/apps/phonglab.svg \
         share/mime/packages/phonglab.xml share/doc/phonglab/README.md share/doc/phonglab/docs/previewer.md \
         share/doc/phonglab/docs/scene-format.md share/doc/phonglab/docs/images/web-page.png \
         share/doc/phonglab/docs/images/previewer.png; do
  check "installs $f" test -s "$prefix/$f"
done
check "the installed phonglab-cli renders" "$prefix/bin/phonglab-cli" render lecture --width 64 --height 36 -o "$work/x.png"
check "the installed phonglab-cli finds phonglab-bench beside it" "$prefix/bin/phonglab-cli" bench lecture --frames 1 --width 32 --height 18
check "the installed phonglab answers --version" "$prefix/bin/phonglab" --version
check "man shows phonglab(1)" sh -c "man -l '$prefix/share/man/man1/phonglab.1' | grep -q 'Whitted'"
check "man shows phonglab-cli(1)" sh -c "man -l '$prefix/share/man/man1/phonglab-cli.1' | grep -q 'validate'"
for page in phonglab phonglab-cli; do
  check "$page(1) renders without warnings" \
    sh -c "test -z \"\$(MANWIDTH=80 man --warnings -l '$prefix/share/man/man1/$page.1' 2>&1 >/dev/null)\""
  check "$page(1) names the installed docs (share/doc/phonglab)" \
    sh -c "MANWIDTH=80 man -l '$prefix/share/man/man1/$page.1' 2>/dev/null | grep -q '/share/doc/phonglab/'"
done
man1=$(MANWIDTH=200 man -l "$prefix/share/man/man1/phonglab.1" 2>/dev/null)
for words in 'Shift+1 .. 9' 'Ctrl+O' 'Ctrl+S' 'Ctrl+Shift+S' 'phonglab/recovery/' '129, 130, 143' 'SIGHUP'; do
  check "phonglab(1) tells of $words" grep -qF -- "$words" <<<"$man1"
done
if command -v desktop-file-validate >/dev/null; then
  check "the desktop entry is valid" desktop-file-validate "$prefix/share/applications/phonglab.desktop"
fi
desktop=$prefix/share/applications/phonglab.desktop
check "the desktop entry claims the scene type (application/x-phonglab-scene)" \
  grep -qE '^MimeType=(.*;)?application/x-phonglab-scene;' "$desktop"
check "the desktop entry no longer claims every JSON file (application/json)" \
  sh -c "! grep -q 'application/json' '$desktop'"
mime=$prefix/share/mime/packages/phonglab.xml
# xmllint (libxml2-utils) and update-mime-database (shared-mime-info) are in tools/dev.sh's packages.
check "the MIME package is well-formed XML" xmllint --noout "$mime"
check "the MIME package defines application/x-phonglab-scene by *.phonglab.json" \
  sh -c "grep -q '<mime-type type=\"application/x-phonglab-scene\">' '$mime' && grep -q 'pattern=\"\\*.phonglab.json\"' '$mime'"
cp -r "$prefix/share/mime" "$work/mime"
update-mime-database "$work/mime" >/dev/null 2>&1
check "update-mime-database takes it (globs2: *.phonglab.json)" \
  grep -qx '[0-9]*:application/x-phonglab-scene:\*\.phonglab\.json' "$work/mime/globs2"
# phonglab --help (no window needed): every option's text starts in one column, continuation
# lines too.
columns=$("$prefix/bin/phonglab" --help | awk '
  /^options:/ { on = 1; next }
  on && /^  --/ { match($0, /^  --[^ ]+( [A-Z]+)?  +/); print RLENGTH + 1; next }
  on && /^   +[^ ]/ { match($0, /^ +/); print RLENGTH + 1 }' | sort -u)
check "phonglab --help: the options' text in one column (columns: $(echo $columns))" test "$(wc -w <<<"$columns")" = 1
check "the icon is well-formed SVG" grep -q '</svg>' "$prefix/share/icons/hicolor/scalable/apps/phonglab.svg"

(cd "$BUILD_DIR" && cpack -G DEB -B "$work/package" >"$work/cpack.log" 2>&1)
deb=$(ls "$work"/package/phonglab_*.deb 2>/dev/null | head -n 1)
check "cpack -G DEB makes a package ($(basename "${deb:-none}"))" test -s "${deb:-/nonexistent}"
if [ -n "$deb" ]; then
  contents=$(dpkg-deb -c "$deb")
  for f in ./usr/bin/phonglab ./usr/bin/phonglab-cli ./usr/bin/phonglab-bench ./usr/share/man/man1/phonglab.1 \
           ./usr/share/applications/phonglab.desktop ./usr/share/icons/hicolor/scalable/apps/phonglab.svg \
           ./usr/share/mime/packages/phonglab.xml ./usr/share/doc/phonglab/README.md; do
    check "the package holds ${f#.}" grep -q " $f\$" <<<"$contents"
  done
  check "the package depends on the libraries it links (libglfw3)" sh -c "dpkg-deb -f '$deb' Depends | grep -q libglfw"
  if [ "$(id -u)" = 0 ] && ! dpkg-query -W phonglab >/dev/null 2>&1; then
    check "dpkg installs the package" dpkg -i "$deb"
    check "the installed package runs (/usr/bin/phonglab-cli)" /usr/bin/phonglab-cli render lecture --width 32 --height 18 -o "$work/y.png"
    check "dpkg removes it" dpkg -r phonglab
    check "nothing of it is left (/usr/bin/phonglab-cli, the desktop entry, the MIME package)" \
      sh -c '! test -e /usr/bin/phonglab-cli && ! test -e /usr/share/applications/phonglab.desktop &&
             ! test -e /usr/share/mime/packages/phonglab.xml'
  else
    echo "  skip  dpkg install and removal (not root, or a phonglab package is installed)"
  fi
fi
echo "install tests: $failures failure(s)"
((failures == 0))
