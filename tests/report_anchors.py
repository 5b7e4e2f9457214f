#!/usr/bin/env python3
"""report_anchors.py PAGE [--self-contained]: check a report page with
html.parser. Every '#' link (the contents tree's and the rest) must name an
element id on the page; the contents must reach down to views (a <details>
section); with --self-contained no src/href may point outside the file
(only '#...' and data: URIs) and no <script>/<link> may load anything.
Prints one line per problem and 'anchors: N contents links, M ids'; exit 1
on a problem."""
import sys
from html.parser import HTMLParser


class Page(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids, self.links, self.toc, self.refs = set(), [], [], []
        self.in_toc = 0
        self.details_ids = set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
            if tag == "details":
                self.details_ids.add(a["id"])
        if tag == "nav" and "toc" in (a.get("class") or ""):
            self.in_toc = 1
        for k in ("src", "href"):
            if k in a and a[k] is not None:
                self.refs.append((tag, k, a[k]))
                if k == "href" and a[k].startswith("#"):
                    self.links.append(a[k][1:])
                    if self.in_toc:
                        self.toc.append(a[k][1:])

    def handle_endtag(self, tag):
        if tag == "nav":
            self.in_toc = 0


def main():
    page, self_contained = sys.argv[1], "--self-contained" in sys.argv[2:]
    p = Page()
    with open(page, encoding="utf-8") as f:
        p.feed(f.read())
    bad = 0
    if len(p.toc) < 5:
        print(f"FAIL only {len(p.toc)} links in the contents")
        bad += 1
    for l in p.links:
        if l not in p.ids:
            print(f"FAIL link #{l} names no element")
            bad += 1
    if not any(t in p.details_ids for t in p.toc):
        print("FAIL the contents reach no view (no <details> section listed)")
        bad += 1
    if self_contained:
        for tag, k, v in p.refs:
            if not (v.startswith("#") or v.startswith("data:")):
                print(f"FAIL external reference <{tag} {k}=\"{v[:80]}\">")
                bad += 1
    print(f"anchors: {len(p.toc)} contents links, {len(p.links)} '#' links, {len(p.ids)} ids")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
