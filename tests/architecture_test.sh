#!/usr/bin/env bash
# docs/architecture.md names every part of the tree: every folder of src/
# (src/dem's folders by job among them), every header (public and private),
# every page of web/, every page of docs/ and every example scene, each as
# `name.ext`, `name.*` or `name` in backticks (a folder as `src/dem/model/`).
# Usage: architecture_test.sh REPO_ROOT. It first checks that it catches a
# planted folder and a planted header the page does not name, so it cannot
# pass vacuously.
set -euo pipefail
root="$1"
doc="$root/docs/architecture.md"

# Prints what the page $2 does not name in the tree under $1; returns 1 when anything.
check_tree() {
  local tree="$1" page="$2" bad=0 dir file stem
  while IFS= read -r dir; do
    grep -qF "\`${dir#"$tree"/}/\`" "$page" || { echo "architecture.md: no word of the folder ${dir#"$tree"/}/"; bad=1; }
  done < <(find "$tree/src" -mindepth 1 -type d | sort)
  while IFS= read -r file; do
    stem=$(basename "$file"); stem="${stem%.*}"
    grep -qE "\`([a-z_/]*/)?$stem(\.|\`)" "$page" || { echo "architecture.md: no word of ${file#"$tree"/}"; bad=1; }
  done < <(find "$tree/include" "$tree/src" -name '*.hpp' -o -name '*.inl' | sort;
           find "$tree/web" -maxdepth 1 -name '*.js' | sort;
           find "$tree/docs" -maxdepth 1 -name '*.md' ! -name architecture.md | sort;
           find "$tree/examples/scenes" -maxdepth 1 -name '*.toml' 2>/dev/null | sort)
  return $bad
}

planted=$(mktemp -d)
trap 'rm -rf "$planted"' EXIT
mkdir -p "$planted/src/dem/unnamed" "$planted/include/gjkdem/dem" "$planted/web" "$planted/docs"
printf '#pragma once\n' >"$planted/include/gjkdem/dem/unnamed_header.hpp"
if check_tree "$planted" "$doc" >/dev/null; then
  echo "architecture: the check missed a planted folder and header" >&2
  exit 1
fi
check_tree "$root" "$doc"
echo "architecture: docs/architecture.md names every folder, header, page and example scene"
