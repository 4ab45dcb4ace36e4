#!/usr/bin/env bash
# check_docs.sh: fails when the documentation falls behind the code. (1) Every long option (--xyz)
# that `montecl <command> --help` prints, for every command, must appear in that command's section
# of docs/usage.md ("## <command>"); (2) every relative markdown link in README.md and docs/*.md
# must point at a file or folder that exists; (3) docs/scene-format.md's render settings table must
# be the code's (`montecl settings --markdown`). Prints one line per problem and exits 1 if there is any, else 0.
# Usage: tests/check_docs.sh MONTECL_EXE SOURCE_DIR   (CTest runs it: CMakeLists.txt)
set -u
exe=${1:?usage: check_docs.sh MONTECL_EXE SOURCE_DIR}
src=${2:?usage: check_docs.sh MONTECL_EXE SOURCE_DIR}
usage="$src/docs/usage.md"
problems=0
fail() { echo "check_docs: $*"; problems=$((problems + 1)); }

[ -f "$usage" ] || { echo "check_docs: $usage is missing"; exit 1; }

# (1) Options. Each command's --help, then every --long-option in it.
commands=("" devices render merge integrate conformance bench generate "generate terrain" settings)
for cmd in "${commands[@]}"; do
  # shellcheck disable=SC2086  # "generate terrain" is two words on purpose
  if ! help=$("$exe" $cmd --help 2>&1); then
    fail "'montecl ${cmd:+$cmd }--help' failed: $(printf '%s' "$help" | head -1)"
    continue
  fi
  # A command's options must be in its own section ("## render" ... up to the next "## "); the
  # top-level options anywhere in the file.
  section=${cmd%% *}
  if [ -n "$section" ]; then
    text=$(awk -v h="## $section" '$0 == h { on = 1; next } /^## / { on = 0 } on' "$usage")
    [ -n "$text" ] || { fail "docs/usage.md has no section '## $section'"; continue; }
    where="its section '## $section' of docs/usage.md"
  else
    text=$(cat "$usage")
    where="docs/usage.md"
  fi
  while IFS= read -r opt; do
    [ -n "$opt" ] || continue
    [ -n "$section" ] && [ "$opt" = --help ] && continue  # every command's; documented once, on top
    # The option must appear as a whole word: --checkpoint does not count as --checkpoint-every.
    printf '%s\n' "$text" | grep -qE -- "${opt}([^a-zA-Z0-9-]|\$)" ||
      fail "montecl ${cmd:+$cmd }--help has ${opt}, which $where does not mention"
  done < <(printf '%s\n' "$help" | grep -oE -- '--[a-zA-Z][a-zA-Z0-9-]*' | sort -u)
done

# (3) The render settings table of docs/scene-format.md, between its markers, is the one the
# settings table in the code prints (`montecl settings --markdown`: scene/render_settings.cpp).
format="$src/docs/scene-format.md"
documented=$(awk '/<!-- render-settings:end -->/ { on = 0 } on; /<!-- render-settings:begin -->/ { on = 1 }' "$format")
if ! generated=$("$exe" settings --markdown 2>&1); then
  fail "'montecl settings --markdown' failed: $(printf '%s' "$generated" | head -1)"
elif [ "$documented" != "$generated" ]; then
  fail "docs/scene-format.md's render settings table differs from 'montecl settings --markdown' (paste its output between the markers):"
  diff <(printf '%s\n' "$documented") <(printf '%s\n' "$generated") | sed 's/^/  /'
fi

# (2) Relative links: ](target) outside fenced code blocks; http(s)/mailto and in-page anchors
# (#...) are not files. The target is relative to the linking file's folder; "#anchor" and a
# "title" after the path are dropped.
for md in "$src/README.md" "$src"/docs/*.md; do
  [ -f "$md" ] || continue
  dir=$(dirname "$md")
  rel=${md#"$src"/}
  while IFS= read -r target; do
    target=${target%% *}
    target=${target%%#*}
    [ -n "$target" ] || continue
    case "$target" in
      http://* | https://* | mailto:* | ftp://*) continue ;;
    esac
    [ -e "$dir/$target" ] || fail "$rel links to $target, which does not exist"
  done < <(awk '/^[[:space:]]*```/ { fenced = !fenced; next } !fenced' "$md" |
           grep -oE '\]\([^)]+\)' | sed -E 's/^\]\((.*)\)$/\1/; s/^<(.*)>$/\1/')
done

if [ "$problems" -gt 0 ]; then
  echo "check_docs: $problems problem(s)"
  exit 1
fi
echo "check_docs: every option of every --help is in docs/usage.md; every relative link resolves"
