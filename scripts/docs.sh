#!/usr/bin/env bash
# Builds the documentation site (mkdocs.yml, docs/) into build/site/ with Debian's mkdocs and
# mkdocs-material, strictly: a link to a missing page fails the build. Open build/site/index.html.
# Usage: ./scripts/docs.sh [SITE_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
site="${1:-$root/build/site}"
if ! command -v mkdocs >/dev/null; then
  echo "docs.sh: mkdocs not found; ./scripts/install-deps.sh installs mkdocs and mkdocs-material" >&2
  exit 1
fi
mkdocs build --strict --config-file "$root/mkdocs.yml" --site-dir "$site"
echo "docs.sh: the site is in $site (open $site/index.html)"
