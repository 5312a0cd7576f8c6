# Sourced by tools/*_figures.sh: the repository root ($here), the radiant
# binary ($radiant, from the build folder given as the script's first
# argument, default build), the figures folder ($out) and a scratch folder
# ($work) removed on exit.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[1]}")/.." && pwd)
radiant="${1:-$here/build}/radiant"
out="$here/docs/images"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
