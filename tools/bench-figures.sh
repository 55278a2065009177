#!/usr/bin/env bash
# Regenerates every bench figure and table that README.md shows, in one command:
#
#   tools/bench-figures.sh [BUILD_DIR]      (default: build)
#
# Builds phonglab-cli (Release), runs the full `phonglab-cli bench` (under 15 minutes on 2 cores),
# copies its report, CSV files and SVG plots to docs/bench/, and rewrites the README's tables
# between the <!-- bench:NAME --> and <!-- /bench:NAME --> markers, including the line that
# names the machine, the load and the duration. Run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target phonglab-cli

out="$build/bench-figures"
rm -rf "$out"
load_before=$(cut -d' ' -f1 /proc/loadavg)
start=$SECONDS
"$build/bin/phonglab-cli" bench --out "$out"
seconds=$((SECONDS - start))
load_after=$(cut -d' ' -f1 /proc/loadavg)

mkdir -p docs/bench
rm -f docs/bench/*
cp "$out"/report.md "$out"/*.csv "$out"/*.svg docs/bench/

cpu=$(grep -m1 '^model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
machine="Measured $(date -u +%Y-%m-%d) with \`tools/bench-figures.sh\` (\`phonglab-cli bench --out $out\`,"
machine+=" Release build of commit $commit) on a machine with \`nproc\` = $(nproc), CPU \"$cpu\","
machine+=" load average $load_before before and $load_after after; the full run took $((seconds / 60)) min"
machine+=" $((seconds % 60)) s."
echo "$machine" > docs/bench/machine.md

# Replaces the lines between <!-- bench:NAME --> and <!-- /bench:NAME --> in FILE by SNIPPET.
splice() {
  local file=$1 name=$2 snippet=$3
  awk -v name="$name" -v snippet="$snippet" '
    $0 == "<!-- bench:" name " -->" { print; while ((getline line < snippet) > 0) print line; skip = 1; next }
    $0 == "<!-- /bench:" name " -->" { skip = 0 }
    !skip { print }' "$file" > "$file.tmp"
  mv "$file.tmp" "$file"
}
splice README.md machine docs/bench/machine.md
splice README.md precision "$out/precision_summary.md"
splice README.md savings "$out/savings.md"
echo "$machine"
echo "docs/bench/ and the README's tables are up to date; review with git diff."
