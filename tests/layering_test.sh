#!/usr/bin/env bash
# The layers' arrows point one way: math <- shape <- collide <- contact <- dem <- io <- mpi.
# Fails when a header or source of a layer includes a header of a higher
# layer. Usage: layering_test.sh REPO_ROOT. It first checks that it catches
# a planted violation, so it cannot pass vacuously.
set -euo pipefail
root="$1"
layers=(math shape collide contact dem io mpi)

rank() {
  local i
  for i in "${!layers[@]}"; do [ "${layers[$i]}" = "$1" ] && { echo "$i"; return; }; done
  echo -1
}

# Prints each violation in the tree under $1; returns 1 when there is one.
check_tree() {
  local tree="$1" bad=0 layer file line target
  for layer in "${layers[@]}"; do
    local mine
    mine=$(rank "$layer")
    for file in $(find "$tree/include/gjkdem/$layer" "$tree/src/$layer" -type f \( -name '*.hpp' -o -name '*.cpp' \) 2>/dev/null); do
      while IFS= read -r line; do
        target=$(sed -E 's@.*#include "gjkdem/([a-z_]+)/.*@\1@' <<<"$line")
        if [ "$(rank "$target")" -gt "$mine" ]; then
          echo "layering: ${file#"$tree"/} ($layer) includes $target: $line"
          bad=1
        fi
      done < <(grep -E '^#include "gjkdem/[a-z_]+/' "$file" || true)
    done
  done
  return $bad
}

planted=$(mktemp -d)
trap 'rm -rf "$planted"' EXIT
mkdir -p "$planted/include/gjkdem/shape"
printf '#include "gjkdem/dem/world.hpp"\n' >"$planted/include/gjkdem/shape/bad.hpp"
if check_tree "$planted" >/dev/null; then
  echo "layering: the check missed a planted violation" >&2
  exit 1
fi
check_tree "$root"
echo "layering: every include points down"
