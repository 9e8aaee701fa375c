#!/usr/bin/env bash
# Runs every `build/shadowlab ...` command that README.md shows in its ```sh code blocks, in the order shown, in a
# temporary directory, with the built executable; fails on the first nonzero exit (issue 28: "every command the
# README shows runs, in the order shown, as a test").
#
#   run_readme_commands.sh README.md SHADOWLAB_EXE DATASETS_DIR
#
# - Only lines that start with `build/shadowlab ` inside ```sh blocks are run (a line ending in `\` continues on the
#   next). The set-up commands (`bash scripts/bootstrap.sh ...`) are not: they install packages and build everything.
# - A line carrying the comment `# not run by the README test` is skipped and named (README uses it for
#   `shadowlab view`, which opens a window).
# - `build/shadowlab` is replaced by SHADOWLAB_EXE; `datasets/` is a link to DATASETS_DIR, so the README's relative
#   paths resolve and every output (out/..., the bench cache) lands in the temporary directory.
set -u
readme=$1 exe=$2 datasets=$3
exe=$(realpath "$exe" 2>/dev/null || echo "$exe")
[[ -f $readme && -x $exe && -d $datasets ]] || { echo "usage: $0 README.md SHADOWLAB_EXE DATASETS_DIR" >&2; exit 2; }
skipMarker='# not run by the README test'

commands=()
inBlock=0 pending=''
while IFS= read -r line || [[ -n $line ]]; do
  if [[ $line =~ ^\`\`\` ]]; then
    if ((inBlock)); then inBlock=0; elif [[ $line == '```sh' ]]; then inBlock=1; fi
    continue
  fi
  ((inBlock)) || continue
  if [[ -n $pending ]]; then
    pending+=" ${line}"
  elif [[ $line == build/shadowlab\ * ]]; then
    pending=$line
  else
    continue
  fi
  if [[ $pending == *\\ ]]; then pending=${pending%\\}; continue; fi
  commands+=("$pending")
  pending=''
done < "$readme"

((${#commands[@]} > 0)) || { echo "no build/shadowlab command found in $readme" >&2; exit 1; }

work=$(mktemp -d "${TMPDIR:-/tmp}/shadowlab-readme.XXXXXX")
trap 'rm -rf "$work"' EXIT
ln -s "$(cd "$datasets" && pwd)" "$work/datasets"
cd "$work" || exit 1

run=0 skipped=0
for command in "${commands[@]}"; do
  if [[ $command == *"$skipMarker"* ]]; then
    echo "skipped (marked): $command"
    skipped=$((skipped + 1))
    continue
  fi
  echo "running: $command"
  start=$SECONDS
  # The README's text after `build/shadowlab`, with the executable in its place; comments stay comments.
  bash -c "$(printf '%q' "$exe")${command#build/shadowlab}" > output.log 2>&1
  status=$?
  if ((status != 0)); then
    tail -n 20 output.log
    echo "FAILED (exit $status after $((SECONDS - start)) s): $command" >&2
    exit 1
  fi
  tail -n 1 output.log
  run=$((run + 1))
done
echo "README commands: $run run, $skipped skipped (marked '$skipMarker')"
