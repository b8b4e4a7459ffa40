#!/usr/bin/env bash
# Makes the Python environment src-it's rosbridge tests run roslibpy in: a venv at
# src-it/target/python-venv with requirements.txt installed (pinned). Idempotent: a venv whose
# packages match the requirements is left as it is. Needs python3 with its venv module (Debian:
# python3-venv); .ci/run installs that and calls this before mvn verify.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
venv="$here/../../../target/python-venv"
requirements="$here/requirements.txt"
stamp="$venv/.requirements"
if [[ -x "$venv/bin/python" ]] && cmp -s "$requirements" "$stamp"; then
  exit 0
fi
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-input -r "$requirements"
cp "$requirements" "$stamp"
echo "src-it: Python clients installed in $(cd "$venv" && pwd) ($("$venv/bin/python" -m pip list --format=freeze 2>/dev/null | grep -i '^roslibpy=='))"
