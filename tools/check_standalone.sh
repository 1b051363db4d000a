#!/usr/bin/env bash
# tools/check_standalone.sh — fails when a tracked file refers to something
# outside the repository: design notes kept beside it, an issue tracker's
# numbers, or a path on the machine it was written on. The repository's own
# design document is docs/architecture.md; cite it (or the page that holds
# the fact) instead, or state the fact itself.
#
#   tools/check_standalone.sh      prints each offending line as file:line,
#                                  with what is wrong, and exits 1; exits 0
#                                  when there is none
set -euo pipefail
cd "$(dirname "$0")/.."

# Each pattern (POSIX extended, matched case-insensitively) with the reason
# a match is refused.
patterns=(
  '\.\./shared'
  'shared/(design|style|sketches|reference)'
  'design\.md'
  'style\.md'
  '\bissues? ?#?[0-9]+'
  "\bthe issue('s)?\b"
  '/work/'
)
reasons=(
  'a path into a directory beside the repository'
  'design notes kept outside the repository'
  'a design note kept outside the repository: cite docs/architecture.md'
  'a style guide kept outside the repository: cite docs/architecture.md'
  'an issue number: state the requirement itself'
  'an issue outside the repository: state the requirement itself'
  'an absolute path on the machine the file was written on'
)

# Generated or third-party files, and this script, which must name the patterns.
excluded=(
  ':(exclude)viewer/package-lock.json'
  ':(exclude)tools/check_standalone.sh'
)

found=0
for i in "${!patterns[@]}"; do
  # git grep exits 1 when nothing matches, 2 or more on an error.
  set +e
  matches=$(git grep -n -I -i -E -e "${patterns[$i]}" -- . "${excluded[@]}")
  status=$?
  set -e
  if ((status > 1)); then
    echo "standalone: git grep failed on pattern ${patterns[$i]}" >&2
    exit 2
  fi
  [[ -z "$matches" ]] && continue
  while IFS= read -r line; do
    location=${line%%:*}
    rest=${line#*:}
    location+=":${rest%%:*}"
    text=${rest#*:}
    printf '%s: %s\n    %s\n' "$location" "${reasons[$i]}" "$text"
    found=1
  done <<<"$matches"
done

if ((found)); then
  echo "standalone: the lines above refer to something outside the repository" >&2
  exit 1
fi
echo "standalone: no reference outside the repository"
