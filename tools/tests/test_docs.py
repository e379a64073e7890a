# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""The documentation in doc/: every file is ASCII only (as LAMMPS's own manual), and the output
vector of fix hardsphere/ed has one length everywhere it is stated: the "global vector of N
values" sentence of doc/fix_hardsphere_ed.rst, its f_ID[1] to f_ID[N] range, the number of
enumerated items that follow it, and the "N-value output vector" of doc/README.md. On every
style page that takes keywords, the "keyword = ..." line of the syntax names the keywords the
block below it describes, in the same order."""
import os
import re

import pytest

DOC = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                   "doc")


@pytest.mark.parametrize("name", sorted(os.listdir(DOC)))
def test_doc_file_is_ascii(name):
    with open(os.path.join(DOC, name), "rb") as f:
        data = f.read()
    bad = [(data.count(b"\n", 0, i) + 1, data[i:i + 4]) for i, c in enumerate(data) if c > 127]
    assert not bad, f"doc/{name}: non-ASCII bytes at lines {sorted({l for l, _ in bad})[:10]}"


def enumerated_items_after(text, start):
    """The number of '#.' items of the reStructuredText list that follows position start (the
    list ends at the first unindented line that is not an item)."""
    lines = text[start:].splitlines()[1:]
    n, begun = 0, False
    for line in lines:
        if line.startswith("#. "):
            n, begun = n + 1, True
        elif begun and line and not line[0].isspace():
            break
    return n


def vector_length_statements():
    with open(os.path.join(DOC, "fix_hardsphere_ed.rst")) as f:
        rst = f.read()
    m = re.search(r"global\s+vector\s+of\s+(\d+)\s+values", rst)
    assert m, "doc/fix_hardsphere_ed.rst states no 'global vector of N values'"
    rng = re.search(r"\*f_ID\[1\]\*\s+to\s+\*f_ID\[(\d+)\]\*", rst[m.end():])
    with open(os.path.join(DOC, "README.md")) as f:
        line = next(l for l in f if "(fix_hardsphere_ed.rst)" in l)
    readme = re.search(r"(\d+)-value output vector", line)
    assert rng and readme
    return {"sentence": int(m.group(1)), "range": int(rng.group(1)),
            "items": enumerated_items_after(rst, m.start()), "README.md": int(readme.group(1))}


def test_fix_hardsphere_ed_vector_length_is_the_same_everywhere():
    n = vector_length_statements()
    assert len(set(n.values())) == 1, n


def test_the_item_count_sees_a_missing_item():
    text = "a global vector of 3 values:\n\n#. one\n#. two\n   more of two\n\nAfter.\n#. not this\n"
    assert enumerated_items_after(text, 0) == 2


def keyword_lists(text):
    """(the keywords of the "* keyword = *a* or *b*" line, those described as "*a* value(s) =" in
    the parsed-literal block that follows), or None on a page that takes no keywords"""
    start = text.find("keyword/value pairs may be appended")
    if start < 0:
        return None
    line = re.search(r"^\* keyword = (.*)$", text[start:], re.M)
    listed = re.findall(r"\*([\w/]+)\*", line.group(1)) if line else []
    block = text.index(".. parsed-literal::", start)
    described = []
    for row in text[block:].splitlines()[1:]:
        if row and not row[0].isspace():
            break
        m = re.match(r"\s+\*([\w/]+)\* values? =", row)
        if m:
            described.append(m.group(1))
    return listed, described


@pytest.mark.parametrize("name", sorted(n for n in os.listdir(DOC) if n.endswith(".rst")))
def test_keyword_line_names_every_keyword(name):
    with open(os.path.join(DOC, name)) as f:
        lists = keyword_lists(f.read())
    if lists is None:
        pytest.skip("takes no keywords")
    listed, described = lists
    assert described, f"doc/{name}: no keyword described below the keyword/value pairs"
    assert listed == described, f"doc/{name}: keyword line {listed}, described {described}"


def test_the_keyword_check_sees_a_missing_keyword():
    text = ("* zero or more keyword/value pairs may be appended\n* keyword = *a* or *c*\n\n"
            "  .. parsed-literal::\n\n       *a* value = x\n         x = one\n"
            "       *b* values = y z\n       *c* value = *p* or *q*\n         *p* = p\n\n"
            "Examples\n       *d* value = not this\n")
    assert keyword_lists(text) == (["a", "c"], ["a", "b", "c"])
