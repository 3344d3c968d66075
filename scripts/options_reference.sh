#!/usr/bin/env bash
# The command line's reference, docs/options.md: every command's --help as the tool prints it, so the page cannot
# drift from the parser. Prints it; with --check FILE, fails with the difference when FILE is not what it prints
# (ctest docs.options). Usage: bash scripts/options_reference.sh build/strainwave [--check docs/options.md]
set -euo pipefail
tool=$1
reference() {
  echo "# Command-line options"
  echo
  echo "Every command's \`--help\`, as \`strainwave\` prints it: written by"
  echo "\`bash scripts/options_reference.sh build/strainwave > docs/options.md\`, and a test fails when it is stale. What"
  echo "the commands do and write: [commands.md](commands.md); the case keys: [keys.md](keys.md)."
  local commands
  commands=$("$tool" --help | awk '/^Subcommands:/ { listed = 1; next } listed && NF { print $1 }')
  for cmd in "" $commands; do
    echo
    echo "## \`strainwave${cmd:+ $cmd}\`"
    echo
    echo '```'
    "$tool" $cmd --help | sed -E 's|^Usage: [^ ]+|Usage: strainwave|'
    echo '```'
  done
}
if [ "${2:-}" = --check ]; then
  if ! diff -u "$3" <(reference) >&2; then
    echo "$3 is not the tool's help: bash scripts/options_reference.sh build/strainwave > $3" >&2
    exit 1
  fi
else
  reference
fi
