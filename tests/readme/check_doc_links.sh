#!/usr/bin/env bash
# Every relative link of the project's Markdown pages resolves to a file or directory of the source tree (issue 28:
# README.md, docs/ and each technique's page link each other). External links (scheme:) and in-page anchors (#...)
# are not followed; a link's own #anchor is dropped before the check.
#
#   check_doc_links.sh SOURCE_DIR
set -u
root=$(cd "${1:?usage: $0 SOURCE_DIR}" && pwd) || exit 2
cd "$root" || exit 2
broken=0 checked=0
# Inline links and images, ](target) or ](target "title"), of every page at once: "page:](target)" lines. Code spans
# are not excluded, so pages keep link syntax out of backticks.
mapfile -d '' pages < <(find . \( -path ./.git -o -path './build*' -o -path ./tests/fuzz \) -prune -o -name '*.md' -print0)
((${#pages[@]} > 0)) || { echo "no Markdown page under $root" >&2; exit 1; }
while IFS= read -r hit; do
  page=${hit%%:\](*}
  target=${hit#*:\](}
  target=${target%)}
  target=${target%% *}
  target=${target%%#*}
  [[ -z $target || $target =~ ^[a-zA-Z][a-zA-Z0-9+.-]*: ]] && continue
  checked=$((checked + 1))
  if [[ ! -e ${page%/*}/$target ]]; then
    echo "$page: broken link: $target" >&2
    broken=$((broken + 1))
  fi
done < <(grep -oH '\]([^)]*)' "${pages[@]}")
echo "checked $checked relative links in ${#pages[@]} pages, $broken broken"
((checked > 0 && broken == 0))
