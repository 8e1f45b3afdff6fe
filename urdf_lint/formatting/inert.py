"""The proof of a new layout from the changed file alone, where xacro's rules make it one.

A layout that passed :func:`urdf_lint.formatting.layout.check_same` differs from its source
only in whitespace-only text between elements (and in the whitespace-only content of a
:data:`~urdf_lint.formatting.layout.STRUCTURAL` element it self-closes): elements,
attributes, comments and every other text are the same. What xacro does with whitespace-only
text nodes (xacro 2, whose output urdf-lint's expansion writes unchanged):

* it moves them only with their level (the children of one element): a macro body, the
  content of an ``xacro:if``/``xacro:unless``, the root of an included file and a ``**`` block
  are spliced whole where they are used; a ``*`` block is one element with its own children;
  it never removes one by itself, and never joins one with other text;
* it reads them in one place: before an ``xacro:`` element it removes the comments above it,
  stepping over a text node of at most one newline, and it inserts (moves) one shared
  ``"\\n\\n"`` text node after it when something precedes it (``remove_previous_comments``);
  what it does depends on where the text nodes are and whether each has more than one
  newline, never on the rest of their content;
* it writes them (``xacro.xmlutils.fixed_writexml``) only as the single child of an element
  (``<e> </e>``); an element with more children is written with its whitespace-only text
  nodes left out (its other text on lines of their own).

So :func:`proven` holds a new layout for the same robot, without expanding anything, when
every level whose text changed (all of it whitespace) is one of these:

* it has a plain child element (one xacro never removes): wherever the level lands, that
  element lands with it, so its whitespace-only text is never written. What xacro reads of it
  must still not change: it has no xacro element among its children but ``xacro:attribute``
  and ``xacro:insert_block`` (which do not read the text before them), or the same shape (a
  text node in the same places, each of one newline at most or more as before); and it is
  either kept as an element around its own children (a plain element, not the root element,
  which an include splices, nor a block of a macro call), or, spliced elsewhere, ends with a
  plain element (the elements after it there step back over its last text node only to
  that element);
* it keeps its shape and holds two nodes that reach the robot together (text, plain
  elements): none of its text can be the single child of an element;
* it is the whitespace of a plain structural element (``<link> </link>``, which the canonical
  robot drops as ``<link/>``) kept as an element around its own children.

With ``quiet_reads`` (every file of every model that reads the file passes
:func:`reads_quietly`: each level with an xacro element that reads the text before it holds
two nodes that reach the robot with it), what xacro reads of whitespace never changes what it
writes, and the shape no longer matters: a plain child element, or two such nodes before and
after, suffice.

Anything else (a macro body of only an xacro:if given text nodes, a blank line removed next to
a comment where a file reads loudly, another attribute order) is proved by expanding the models
(:func:`urdf_lint.run.format.prove`). A formatted file is read by xacro as XML (the entry
or an include); the formatter touches ``.urdf`` and ``.xacro`` files only.
"""
from __future__ import annotations

from urdf_lint.formatting.layout import STRUCTURAL, Node

# the parents that keep a child element an element around its own children
KEEPING = ("xacro:macro", "xacro:if", "xacro:unless")
# xacro elements that do not look at the text around them (no remove_previous_comments)
# (not xacro:element: the name it takes may be an xacro one, xacro:if, which it then is)
QUIET = ("xacro:attribute", "xacro:insert_block")


def _joined(nodes: list[Node]) -> list[Node]:
    out: list[Node] = []
    for n in nodes:
        if n[0] == "text" and out and out[-1][0] == "text":
            out[-1] = ("text", out[-1][1] + n[1])
        else:
            out.append(n)
    return out


def _kept(el: Node, parent: Node | None) -> bool:
    """Is the element an element around its own children in every expansion (a plain
    element, not the root, which an include splices, nor a block of a macro call)?"""
    return not el[1].startswith("xacro:") and parent is not None and (
        not parent[1].startswith("xacro:") or parent[1] in KEEPING)


def _reaches(n: Node) -> bool:
    """Does the node reach the robot with the rest of its level, whatever xacro does?"""
    return n[0] == "text" or (n[0] == "el" and not n[1].startswith("xacro:"))


def _shape(nodes: list[Node]) -> list[Node]:
    return [("t", n[1].count("\n") > 1) if n[0] == "text" else n[0] for n in nodes]


def _changed_level(el: Node, parent: Node | None, ka: list[Node], kb: list[Node],
                   quiet_reads: bool) -> str | None:
    """None when the new text of the level ``ka`` -> ``kb`` (the children of ``el``) cannot
    reach the robot."""
    if any(n[1].strip() for n in ka + kb if n[0] == "text"):
        return f"the text of <{el[1]}> differs"
    if not kb and len(ka) == 1:     # <link> </link> -> <link/>
        if el[1] in STRUCTURAL and _kept(el, parent):
            return None
        return f"the whitespace of <{el[1]}> may reach the robot once it is self-closed"
    if quiet_reads:     # what xacro reads of whitespace changes nothing it writes
        if _with_element(ka) or min(_reaching(k) for k in (ka, kb)) >= 2:
            return None
        return f"the whitespace in <{el[1]}> may be the only child of an element"
    if _with_element(ka) and _lands_in_an_element(el, parent, ka, kb):
        return None
    if _shape(ka) != _shape(kb):
        return f"the whitespace in <{el[1]}> changes its shape, which xacro reads"
    if _reaching(ka) < 2:
        return f"the whitespace in <{el[1]}> may be the only child of an element"
    return None


def _reaching(nodes: list[Node]) -> int:
    """How many of the nodes reach the robot."""
    return sum(1 for n in nodes if _reaches(n))


def _with_element(nodes: list[Node]) -> bool:
    """Does an element among the nodes reach the robot?"""
    return any(n[0] == "el" and _reaches(n) for n in nodes)


def _lands_in_an_element(el: Node, parent: Node | None, ka: list[Node], kb: list[Node]) -> bool:
    """Whether a level that reaches the robot with an element (``ka`` -> ``kb``) keeps its
    new whitespace out of it. The element it lands in is written with its whitespace-only
    text left out, wherever that is. xacro reads where the text is next to its own elements
    among the children; and, where the level is spliced into another, from the elements that
    follow it there, stepping back over its last text to a comment (none when the level ends
    with an element)."""
    quiet = all(not n[1].startswith("xacro:") or n[1] in QUIET for n in ka if n[0] == "el")
    last = [n for n in ka if n[0] != "text"][-1]
    ends = last[0] == "el" and _reaches(last)
    return (quiet or _shape(ka) == _shape(kb)) and (_kept(el, parent) or ends)


def _pairs(xs: list[Node], ys: list[Node], parent: Node | None, quiet_reads: bool) -> str | None:
    """None when the nodes (one level, its text left out) read the same to xacro."""
    if len(xs) != len(ys):
        return "the structure differs"
    for x, y in zip(xs, ys, strict=True):
        if x[0] != y[0]:
            return "the structure differs"
        if x[0] == "el":
            if x[1] != y[1] or x[2] != y[2]:    # (attributes in order: xacro evaluates so)
                return f"<{x[1]}> differs"
            why = _same(x, y, parent, quiet_reads)
            if why is not None:
                return why
        elif x != y:
            return "a comment, an instruction or the prolog differs"
    return None


def _same(a: Node, b: Node, parent: Node | None, quiet_reads: bool) -> str | None:
    ka, kb = _joined(a[3]), _joined(b[3])
    why = _pairs([n for n in ka if n[0] != "text"], [n for n in kb if n[0] != "text"], a,
                 quiet_reads)
    if why is not None or ka == kb:
        return why
    return _changed_level(a, parent, ka, kb, quiet_reads)


def proven(old_doc: list[Node], new_doc: list[Node], quiet_reads: bool = False) -> str | None:
    """None when the new layout provably expands to the same robot in every model that reads
    the file; else why the models must be expanded to prove it. ``old_doc`` and ``new_doc``
    are :func:`urdf_lint.formatting.layout.read_document` of the two layouts.
    ``quiet_reads``: every file those models read passes :func:`reads_quietly` (as it is and
    as it will be), so where xacro reads whitespace changes nothing it writes."""
    # (the whitespace around the root element is not read)
    return _pairs([n for n in old_doc if n[0] != "text"], [n for n in new_doc if n[0] != "text"],
                  None, quiet_reads)


# where what reaches the robot depends on the values of args: a branch is proved as taken,
# whatever its condition (the models are expanded with the args they are given only)
CONDITIONAL = ("xacro:if", "xacro:unless")


def unproven_in_branches(old_doc: list[Node], new_doc: list[Node]) -> str | None:
    """None when every level whose whitespace changed inside an ``xacro:if``/``xacro:unless``
    body (at any depth) is proved by the rules of :func:`proven` (which hold whatever the
    condition); else why. Expanding the models proves only the branches their args take:
    ``sim:=true`` from a launch file takes one nobody configured, so such a level is left as
    it is."""
    return _branches([n for n in old_doc if n[0] == "el"],
                     [n for n in new_doc if n[0] == "el"], None, False)


def _branches(xs: list[Node], ys: list[Node], parent: Node | None, taken: bool) -> str | None:
    if len(xs) != len(ys):
        return "the structure differs"
    for a, b in zip(xs, ys, strict=True):
        if a[0] != b[0] or a[1] != b[1]:
            return "the structure differs"
        ka, kb = _joined(a[3]), _joined(b[3])
        inner = taken or a[1] in CONDITIONAL
        why = _branches([n for n in ka if n[0] == "el"], [n for n in kb if n[0] == "el"],
                        a, inner)
        if why is None and inner and ka != kb:
            why = _changed_level(a, parent, ka, kb, False)
            if why is not None:
                why += " (in an xacro:if or xacro:unless body: expanding the models with " \
                       "their args does not prove every branch)"
        if why is not None:
            return why
    return None


def reads_quietly(doc: list[Node]) -> bool:
    """Does every element of the document with an xacro element that reads the whitespace
    before it (``remove_previous_comments``) among its children also hold two nodes that reach
    the robot with it (text, plain elements)? Then, in every model whose files all do, what
    that reading does (which comments go, where xacro's one shared ``"\\n\\n"`` text node ends,
    always in such a level) never changes what xacro writes: such a level is written with
    at least two children, whose whitespace-only text and comments the canonical robot drops."""
    todo = [n for n in doc if n[0] == "el"]
    while todo:
        el = todo.pop()
        kids = el[3]
        loud = any(n[0] == "el" and n[1].startswith("xacro:") and n[1] not in QUIET
                   for n in kids)
        if loud and sum(1 for n in _joined(kids) if _reaches(n)) < 2:
            return False
        todo.extend(n for n in kids if n[0] == "el")
    return True
