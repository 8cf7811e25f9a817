#!/usr/bin/env python3
"""Checks the built documentation as a reader would open it.

    check_site.py HTML_DIR MAN_PAGE

* every local link and every image, script and style sheet a page refers to
  exists (a page, a file, an anchor on the page linked to);
* nothing is loaded from the network: no script, style sheet, font, frame or
  image from another host, in the HTML or in the style sheets;
* the man page renders with man(1) and documents every subcommand the
  program's help lists in the command-line reference.
"""
import html.parser
import os
import re
import subprocess
import sys
import urllib.parse

REMOTE = re.compile(r"^(?:[a-z]+:)?//", re.I)
CSS_URL = re.compile(r"url\(\s*['\"]?([^'\")]+)", re.I)
CSS_IMPORT = re.compile(r"@import\s+['\"]([^'\"]+)", re.I)


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.loads, self.ids = [], [], set()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("name"):
            self.ids.add(attrs["name"])
        if tag == "a" and attrs.get("href"):
            self.links.append(attrs["href"])
        for attr in ("src", "href") if tag in ("script", "img", "iframe", "link", "source") else ():
            if attrs.get(attr):
                self.loads.append(attrs[attr])


def parse(path):
    page = Page()
    with open(path, encoding="utf-8") as f:
        page.feed(f.read())
    return page


def main(html_dir, man_page):
    problems = []
    pages = {}
    for folder, _, files in os.walk(html_dir):
        for name in files:
            path = os.path.join(folder, name)
            if name.endswith(".html"):
                pages[os.path.abspath(path)] = parse(path)
            elif name.endswith(".css"):
                text = open(path, encoding="utf-8", errors="replace").read()
                for url in CSS_URL.findall(text) + CSS_IMPORT.findall(text):
                    if REMOTE.match(url.strip()):
                        problems.append(f"{path}: loads {url} from the network")
    if not pages:
        problems.append(f"{html_dir}: no pages")
    for path, page in sorted(pages.items()):
        here = os.path.dirname(path)
        for url in page.loads:
            if REMOTE.match(url) or url.startswith(("http:", "https:")):
                problems.append(f"{path}: loads {url} from the network")
            elif not url.startswith("data:"):
                target = os.path.normpath(os.path.join(here, urllib.parse.unquote(url.split("?")[0].split("#")[0])))
                if not os.path.exists(target):
                    problems.append(f"{path}: {url} does not exist")
        for url in page.links:
            if REMOTE.match(url) or url.startswith(("mailto:", "http:", "https:", "javascript:")):
                continue
            file, _, anchor = url.partition("#")
            target = os.path.normpath(os.path.join(here, urllib.parse.unquote(file))) if file else path
            if not os.path.exists(target):
                problems.append(f"{path}: link {url} leads nowhere")
            elif anchor and target in pages and urllib.parse.unquote(anchor) not in pages[target].ids:
                problems.append(f"{path}: link {url}: no anchor {anchor} there")
    rendered = subprocess.run(["man", "-l", man_page], capture_output=True, text=True,
                              env={**os.environ, "MANWIDTH": "80", "MANPAGER": "cat", "PAGER": "cat"})
    if rendered.returncode != 0 or "attenuvis" not in rendered.stdout:
        problems.append(f"{man_page}: man -l failed ({rendered.returncode}): {rendered.stderr.strip()}")
    else:
        for command in ("mie", "sigma", "table", "optics", "vg", "scene", "reproduce"):
            if not re.search(rf"attenuvis {command}\b", rendered.stdout):
                problems.append(f"{man_page}: no section for attenuvis {command}")
    for problem in problems:
        print(problem, file=sys.stderr)
    print(f"{len(pages)} pages checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
