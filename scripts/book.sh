#!/usr/bin/env bash
# The morgana book (docs/book, mdBook): installs the pinned mdBook into target/tools once, builds
# the book into target/book, and checks every link in the generated HTML (scripts/check_links.py:
# pages, #fragments, files in the repository, and the README's links; external links for syntax
# only), and that every test "What is checked" names exists. Run by ./scripts/test; open
# target/book/index.html to read it.
set -euo pipefail
cd "$(dirname "$0")/.."

MDBOOK_VERSION=0.5.4
tools="$PWD/target/tools"
mdbook="$tools/bin/mdbook"

installed="$("$mdbook" --version 2>/dev/null || true)"
if [ "$installed" != "mdbook v$MDBOOK_VERSION" ]; then
  echo "book.sh: installing mdbook $MDBOOK_VERSION into $tools (a few minutes, once)" >&2
  cargo install mdbook --version "$MDBOOK_VERSION" --locked --root "$tools"
fi

rm -rf target/book
"$mdbook" build docs/book            # docs/book/book.toml sends the HTML to target/book
python3 scripts/check_links.py --book target/book --repo . --markdown README.md \
  --test-refs docs/book/src/checked.md
