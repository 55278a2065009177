#!/usr/bin/env bash
# The upstairs' shape (docs/architecture.md), checked on the tree:
#   bash tests/check_classes.sh <source dir>
# - no class or struct in apps/ with more than 40 member functions (constructors, operators and
#   deleted ones aside), counted by universal-ctags on the headers;
# - no `friend` in apps/previewer (components get the shell's state and each other by reference);
# - no `scene()` that hands out a mutable Scene outside src/session (the session is its one writer).
set -euo pipefail
root=${1:?source dir}
limit=40
failures=0
command -v ctags >/dev/null || { echo "ctags (universal-ctags) is missing: tools/dev.sh deps installs it"; exit 1; }
ctags --version | grep -q "Universal Ctags" || { echo "ctags is not universal-ctags"; exit 1; }

counts=$(find "$root/apps" -name '*.h' -print0 | xargs -0 ctags -f - --c++-kinds=pf --fields=+sS | awk -F'\t' '
  { cls = ""
    for (i = 4; i <= NF; i++) if ($i ~ /^(class|struct):/) cls = $i
    if (cls == "") next
    sub(/^(class|struct):/, "", cls)
    n = split(cls, parts, "::"); base = parts[n]
    if ($1 == base || $1 == "~" base || $1 ~ /^operator/ || $3 ~ /= *delete/) next
    count[cls]++ }
  END { for (c in count) print count[c], c }' | sort -rn)
echo "$counts" | head -3 | sed 's/^/member functions: /'
while read -r n cls; do
  [ -z "$n" ] && continue
  if [ "$n" -gt "$limit" ]; then echo "FAIL $cls has $n member functions (at most $limit)"; failures=$((failures + 1)); fi
done <<<"$counts"

if grep -rnE '^\s*friend\b' "$root/apps/previewer" --include='*.h' --include='*.cpp'; then
  echo "FAIL a friend in apps/previewer (above)"; failures=$((failures + 1))
fi
if grep -rnE '(^|[^t] )Scene& scene\(\)( |;|\{)' "$root/src" "$root/apps" --include='*.h' | grep -v '^[^:]*src/session/' | grep -v 'const Scene& scene() const'; then
  echo "FAIL a mutable scene() outside the session (above)"; failures=$((failures + 1))
fi
[ "$failures" -eq 0 ] && echo "the upstairs' shape holds"
exit "$failures"
