#!/usr/bin/env bash
# Serves the viewer and one .srm file, and prints the viewer's URL:
#   bash web/serve.sh FILE.srm [--port N] [--rate BYTES_PER_SECOND]
# --rate sends the file slowly, to watch it refine. Builds web/dist first
# when it is missing.
set -euo pipefail
web="$(cd "$(dirname "$0")" && pwd)"

# The file is checked before a build that can take a minute.
file=""
args=("$@")
for ((i = 0; i < ${#args[@]}; ++i)); do
  case "${args[i]}" in
    --port|--rate|--chunk|--drop-after) i=$((i + 1)) ;;
    -*) ;;
    *) [ -n "$file" ] || file="${args[i]}" ;;
  esac
done
if [ -z "$file" ]; then
  echo "usage: bash web/serve.sh FILE.srm [--port N] [--rate BYTES_PER_SECOND]" >&2
  exit 2
fi
if [ ! -f "$file" ]; then
  echo "web/serve.sh: $file: no such file" >&2
  exit 1
fi

if [ ! -f "$web/dist/index.js" ] || [ ! -d "$web/node_modules/three" ]; then
  bash "$web/build.sh"
fi
exec node "$web/tools/serve.mjs" "$@"
