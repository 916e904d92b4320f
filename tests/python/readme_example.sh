#!/usr/bin/env bash
# Runs the README's Python example as written: the first ```python block of README.md, in a
# fresh folder that sees the repository's scenes/ (the example's paths are relative to the
# repository root).
#   readme_example.sh PYTHON README.md WORK_DIR
set -euo pipefail
python=$1 readme=$2 work=$3
root=$(cd "$(dirname "$readme")" && pwd)
rm -rf "$work"
mkdir -p "$work"
ln -s "$root/scenes" "$work/scenes"
awk '/^```python$/ { inside = 1; next } inside && /^```$/ { exit } inside { print }' "$readme" \
  >"$work/example.py"
[[ -s "$work/example.py" ]] || { echo "no \`\`\`python block in $readme" >&2; exit 1; }
cd "$work"
"$python" example.py
test -s cornell-python.png
