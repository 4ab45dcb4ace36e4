#!/usr/bin/env bash
# check_docs.sh: fails when the documentation falls behind the code (reads README.md, docs/*.md,
# the tree and the two binaries' own tables; writes nothing). (1) Every long option (--xyz) that
# `montecl <command> --help` prints, for every command, must appear in that command's section of
# docs/usage.md ("## <command>"); (2) every relative markdown link in README.md and docs/*.md must
# point at a file or folder that exists; (3) docs/scene-format.md's render settings table must be
# the code's (`montecl settings --markdown`), and docs/architecture.md's kinds tables the kind
# tables' (`montecl kinds --markdown`); (4) docs/architecture.md must name every header under
# kernels/ (by file name, or a `*_pattern.h` that matches it) and every folder under host/;
# (5) every count the docs state of test cases ("N doctest cases", "N test cases"), test files
# ("N test files"), material or light kinds ("N light kinds", digits or words) must be the tree's.
# Prints one line per problem and exits 1 if there is any, else 0.
# Usage: tests/check_docs.sh MONTECL_EXE SOURCE_DIR [MONTECL_TESTS_EXE]   (CTest runs it: CMakeLists.txt;
# without MONTECL_TESTS_EXE the test cases are counted as the TEST_CASE lines under tests/)
set -u
exe=${1:?usage: check_docs.sh MONTECL_EXE SOURCE_DIR}
src=${2:?usage: check_docs.sh MONTECL_EXE SOURCE_DIR}
tests_exe=${3:-}
usage="$src/docs/usage.md"
problems=0
fail() { echo "check_docs: $*"; problems=$((problems + 1)); }

[ -f "$usage" ] || { echo "check_docs: $usage is missing"; exit 1; }

# (1) Options. Each command's --help, then every --long-option in it.
commands=("" devices render merge integrate conformance bench generate "generate terrain" settings kinds)
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

# (3) Generated tables: the text between a doc's markers is what the command prints.
#   docs/scene-format.md  <!-- render-settings:begin/end -->  montecl settings --markdown (scene/render_settings.cpp)
#   docs/architecture.md  <!-- kinds:begin/end -->            montecl kinds --markdown (material_kinds.h, light_kinds.h)
check_generated() {
  local doc=$1 marker=$2 what=$3
  shift 3
  local documented generated
  documented=$(awk -v b="<!-- $marker:begin -->" -v e="<!-- $marker:end -->" '$0 == e { on = 0 } on; $0 == b { on = 1 }' "$src/$doc")
  if ! generated=$("$exe" "$@" 2>&1); then
    fail "'montecl $*' failed: $(printf '%s' "$generated" | head -1)"
  elif [ -z "$documented" ]; then
    fail "$doc has no $what between <!-- $marker:begin --> and <!-- $marker:end --> (paste 'montecl $*' there)"
  elif [ "$documented" != "$generated" ]; then
    fail "$doc's $what differs from 'montecl $*' (paste its output between the markers):"
    diff <(printf '%s\n' "$documented") <(printf '%s\n' "$generated") | sed 's/^/  /'
  fi
}
check_generated docs/scene-format.md render-settings "render settings table" settings --markdown
check_generated docs/architecture.md kinds "kinds tables" kinds --markdown

# (4) docs/architecture.md names every kernel header and every host folder.
arch="$src/docs/architecture.md"
named=$(grep -oE '`[^`]*\.h`' "$arch" | tr -d '`' | sed 's|.*/||' | sort -u)
for h in "$src"/kernels/*/*.h "$src"/kernels/*.h; do
  [ -f "$h" ] || continue
  base=$(basename "$h")
  found=0
  while IFS= read -r n; do
    # shellcheck disable=SC2053  # a named `*_lanes.h` is a pattern on purpose
    if [ "$n" = "$base" ] || { [[ $n == *'*'* ]] && [[ $base == $n ]]; }; then found=1; break; fi
  done <<<"$named"
  [ "$found" = 1 ] || fail "docs/architecture.md does not name ${h#"$src"/} (a \`$base\` row in its kernels tables)"
done
for d in "$src"/host/*/; do
  dir=$(basename "$d")
  grep -qE "(^|[^a-zA-Z0-9_])$dir/" "$arch" || fail "docs/architecture.md does not name host/$dir/ (its map)"
done

# (5) Counts stated in the docs. The tree's: test cases (doctest's own count, else TEST_CASE
# lines), test files (tests/test_*.cpp), kinds (the counts `montecl kinds --markdown` prints).
number() {  # a count as the docs write it: digits (thousands commas allowed) or a word to twenty
  local w
  w=$(printf '%s' "$1" | tr 'A-Z' 'a-z' | tr -d ',')
  case "$w" in
    one) echo 1 ;; two) echo 2 ;; three) echo 3 ;; four) echo 4 ;; five) echo 5 ;; six) echo 6 ;;
    seven) echo 7 ;; eight) echo 8 ;; nine) echo 9 ;; ten) echo 10 ;; eleven) echo 11 ;; twelve) echo 12 ;;
    thirteen) echo 13 ;; fourteen) echo 14 ;; fifteen) echo 15 ;; sixteen) echo 16 ;; seventeen) echo 17 ;;
    eighteen) echo 18 ;; nineteen) echo 19 ;; twenty) echo 20 ;; *) echo "$w" ;;
  esac
}
if [ -n "$tests_exe" ]; then
  cases=$("$tests_exe" --count 2>&1 | grep -oE 'passing the current filters: [0-9]+' | grep -oE '[0-9]+$')
else
  cases=$(cat "$src"/tests/*.cpp | grep -cE '^ *TEST_CASE\(')
fi
files=$(find "$src/tests" -maxdepth 1 -name 'test_*.cpp' | wc -l)
kinds=$("$exe" kinds --markdown 2>/dev/null)
materials=$(printf '%s\n' "$kinds" | grep -oE '^[0-9]+ material kinds' | grep -oE '^[0-9]+')
lights=$(printf '%s\n' "$kinds" | grep -oE '^[0-9]+ light kinds' | grep -oE '^[0-9]+')
words='[0-9][0-9,]*|[Oo]ne|[Tt]wo|[Tt]hree|[Ff]our|[Ff]ive|[Ss]ix|[Ss]even|[Ee]ight|[Nn]ine|[Tt]en|[Ee]leven|[Tt]welve|[Tt]hirteen|[Ff]ourteen|[Ff]ifteen|[Ss]ixteen|[Ss]eventeen|[Ee]ighteen|[Nn]ineteen|[Tt]wenty'
for md in "$src/README.md" "$src"/docs/*.md; do
  rel=${md#"$src"/}
  while IFS=: read -r line stated; do
    n=$(number "${stated%% *}")
    case "$stated" in
      *" doctest cases" | *" test cases") want=$cases what="test cases" ;;
      *" test files") want=$files what="test files (tests/test_*.cpp)" ;;
      *" material kinds") want=$materials what="material kinds" ;;
      *" light kinds") want=$lights what="light kinds" ;;
      *) continue ;;
    esac
    [ "$n" = "$want" ] || fail "$rel:$line says '$stated'; the tree has $want $what"
  done < <(grep -noE "(^|[^0-9A-Za-z])($words) (doctest cases|test cases|test files|material kinds|light kinds)" "$md" |
           sed -E 's/^([0-9]+):[^0-9A-Za-z]?/\1:/')
done

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
echo "check_docs: every option of every --help is in docs/usage.md; every relative link resolves; the generated tables, the map and the counts match the tree"
