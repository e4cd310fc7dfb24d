#!/usr/bin/env python3
"""Check every link in a built mdBook (HTML), stdlib only.

    scripts/check_links.py --book target/book --repo . [--markdown README.md] [--test-refs PAGE.md]

For every href/src in every .html file under --book:

- `#fragment` and `page.html#fragment`: the page must exist and carry that id (an `id`
  attribute, or `name` on <a>); a bare `#` is the top of the page.
- a relative path that stays inside the book: the file (or folder) must exist.
- a relative path that leaves the book but stays inside the repository (`../../examples/x.toml`
  from target/book): the repository file or folder must exist. Such links are valid when the
  book is read where it was built, inside the repository.
- http(s) links: checked for syntax only (scheme, host, no spaces); the machine that runs the
  tests may have no network. mailto: needs an address; data: and javascript: are ignored.
- anything else (absolute paths, unknown schemes, paths leaving the repository) is an error.

A page's <base href="/"> (mdBook's 404 page) makes its relative links start at the book's root.

--markdown FILE ... also checks the relative links of Markdown files outside the book (the
README): `[text](path)` and `![alt](path)` must name existing files (fragments are not checked
there).

--test-refs FILE ... checks that every test a page names as `tests/x.rs::function` or
`src/.../y.rs::function` (and `::function` after one of those in the same line) exists: the file
is there and defines that function right after a #[test] attribute.

Exit status 0 when everything resolves, 1 otherwise (each broken link is printed with its page).
"""

from __future__ import annotations

import argparse
import re
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

LINK_ATTRS = {"a": "href", "link": "href", "area": "href", "img": "src", "script": "src",
              "iframe": "src", "source": "src", "audio": "src", "video": "src", "embed": "src"}
HOST = re.compile(r"^[A-Za-z0-9.-]+(:[0-9]+)?$")
TEST_REF = re.compile(r"`((?:tests|src)/[\w/.-]+\.rs)?::(\w+)`")
MD_LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


class Page(HTMLParser):
    """The links, ids and <base> of one HTML page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.links: list[tuple[int, str]] = []
        self.ids: set[str] = set()
        self.base: str | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = {k: (v or "") for k, v in attrs}
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and "name" in a:
            self.ids.add(a["name"])
        if tag == "base" and "href" in a and self.base is None:
            self.base = a["href"]
        attr = LINK_ATTRS.get(tag)
        if attr and attr in a:
            self.links.append((self.getpos()[0], a[attr].strip()))

    handle_startendtag = handle_starttag


def parse(path: Path) -> Page:
    page = Page()
    page.feed(path.read_text(encoding="utf-8", errors="replace"))
    page.close()
    return page


def inside(path: Path, root: Path) -> bool:
    try:
        path.relative_to(root)
        return True
    except ValueError:
        return False


def check_external(url: str) -> str | None:
    parts = urlsplit(url)
    if parts.scheme in ("http", "https"):
        if not parts.netloc or not HOST.match(parts.netloc.rsplit("@", 1)[-1]):
            return "malformed host"
        if any(c.isspace() for c in url):
            return "whitespace in URL"
        return None
    if parts.scheme == "mailto":
        return None if "@" in parts.path else "mailto without an address"
    return f"scheme '{parts.scheme}' is not allowed"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--book", required=True, type=Path, help="the built book (HTML output folder)")
    ap.add_argument("--repo", required=True, type=Path, help="the repository root")
    ap.add_argument("--markdown", nargs="*", default=[], type=Path, help="Markdown files to check too")
    ap.add_argument("--test-refs", nargs="*", default=[], type=Path, help="pages whose test names to check")
    args = ap.parse_args()
    book, repo = args.book.resolve(), args.repo.resolve()
    pages = sorted(book.rglob("*.html"))
    if not pages:
        print(f"check_links: no HTML pages under {book}", file=sys.stderr)
        return 1
    parsed = {p: parse(p) for p in pages}
    ids_cache: dict[Path, set[str]] = {p: parsed[p].ids for p in pages}
    broken: list[str] = []
    counts = {"internal": 0, "fragment": 0, "repository": 0, "external": 0}

    def ids_of(target: Path) -> set[str]:
        if target not in ids_cache:
            ids_cache[target] = parse(target).ids
        return ids_cache[target]

    for page_path in pages:
        page = parsed[page_path]
        rel_page = page_path.relative_to(book)
        start = book if page.base == "/" else page_path.parent
        for line, url in page.links:
            where = f"{rel_page}:{line}: {url!r}"
            if url == "" or url.startswith(("data:", "javascript:")):
                continue
            parts = urlsplit(url)
            if parts.scheme or url.startswith("//"):
                problem = check_external(url if parts.scheme else "https:" + url)
                if problem:
                    broken.append(f"{where}: {problem}")
                counts["external"] += 1
                continue
            if parts.path.startswith("/"):
                broken.append(f"{where}: absolute path (breaks outside a web server root)")
                continue
            fragment = unquote(parts.fragment)
            if parts.path == "":
                target = page_path
            else:
                target = (start / unquote(parts.path)).resolve()
            if inside(target, book):
                if not target.exists():
                    broken.append(f"{where}: no such file in the book ({target.relative_to(book)})")
                    continue
                if parts.path:
                    counts["internal"] += 1
                if fragment and target.suffix == ".html":
                    counts["fragment"] += 1
                    if fragment not in ids_of(target):
                        broken.append(f"{where}: no id '{fragment}' in {target.relative_to(book)}")
                continue
            if inside(target, repo):
                if not target.exists():
                    broken.append(f"{where}: no such file in the repository ({target.relative_to(repo)})")
                    continue
                counts["repository"] += 1
                if fragment and target.suffix == ".html" and fragment not in ids_of(target):
                    broken.append(f"{where}: no id '{fragment}' in {target.relative_to(repo)}")
                continue
            broken.append(f"{where}: leaves the repository ({target})")

    for md in args.markdown:
        text = md.read_text(encoding="utf-8")
        for m in MD_LINK.finditer(text):
            url = m.group(1).strip()
            line = text.count("\n", 0, m.start()) + 1
            where = f"{md}:{line}: {url!r}"
            parts = urlsplit(url)
            if parts.scheme or url.startswith("//"):
                problem = check_external(url if parts.scheme else "https:" + url)
                if problem:
                    broken.append(f"{where}: {problem}")
                counts["external"] += 1
                continue
            if not parts.path:
                continue
            target = (md.resolve().parent / unquote(parts.path)).resolve()
            if not inside(target, repo) or not target.exists():
                broken.append(f"{where}: no such file in the repository")
            else:
                counts["repository"] += 1

    counts["tests"] = 0
    sources: dict[Path, str] = {}
    for md in args.test_refs:
        for n, line in enumerate(md.read_text(encoding="utf-8").splitlines(), 1):
            current = None
            for m in TEST_REF.finditer(line):
                if m.group(1):
                    current = repo / m.group(1)
                where = f"{md}:{n}: {m.group(0)}"
                if current is None:
                    broken.append(f"{where}: no file named before it on the line")
                    continue
                if not current.is_file():
                    broken.append(f"{where}: {current.relative_to(repo)} does not exist")
                    continue
                text = sources.setdefault(current, current.read_text(encoding="utf-8"))
                if not re.search(r"#\[test\](?:\s*#\[[^\]]*\])*\s*fn " + m.group(2) + r"\s*\(", text):
                    broken.append(f"{where}: no test fn {m.group(2)} in {current.relative_to(repo)}")
                    continue
                counts["tests"] += 1

    total = sum(counts.values()) - counts["tests"]
    for b in broken:
        print(f"check_links: broken: {b}", file=sys.stderr)
    print(
        f"check_links: {len(pages)} pages, {total} links checked "
        f"({counts['internal']} in the book, {counts['fragment']} fragments, "
        f"{counts['repository']} into the repository, {counts['external']} external, syntax only), "
        f"{counts['tests']} test names; {len(broken)} broken"
    )
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
