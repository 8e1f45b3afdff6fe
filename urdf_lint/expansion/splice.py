"""Linear-time node replacement for xacro's minidom tree.

Stock xacro replaces a macro call (or an ``xacro:if``, an include, an ``insert_block``) by
inserting the new children one at a time with minidom's ``insertBefore``, then removing the
call with ``removeChild``. Both look the reference node up with ``list.index`` / ``list.remove``,
which compare every sibling before it, so a flat robot of N macro calls costs O(N²) and a
recursive macro of depth D moves every node D times with a scan each time.

:func:`replace_node` and :func:`remove_previous_comments` do the same edits as xacro's (same
resulting tree, so the output stays byte-identical) with one slice assignment, finding the
node from a per-parent position hint: xacro walks siblings in order, so the next node is almost
always right after the last edit. Anything unusual (documents, fragments, node types a parent
cannot hold) goes to the original functions, which raise the DOM's own errors.
"""
from __future__ import annotations

import xml.dom
from typing import Any
from xml.dom import minidom

_ELEMENT = xml.dom.Node.ELEMENT_NODE
_TEXT = xml.dom.Node.TEXT_NODE
_COMMENT = xml.dom.Node.COMMENT_NODE
_WINDOW_BACK, _WINDOW_AHEAD = 16, 48

# id(parent) -> (parent, index of the last edit); the parent is held so its id is not reused.
_hints: dict[int, tuple[Any, int]] = {}
_orig: dict[str, Any] = {}


def reset() -> None:
    """Forget the position hints (call once per expansion)."""
    _hints.clear()


def _index_of(parent: Any, node: Any) -> int:
    kids = parent.childNodes
    h = _hints.get(id(parent))
    if h is not None and h[0] is parent:
        i = h[1]
        for j in range(max(0, i - _WINDOW_BACK), min(len(kids), i + _WINDOW_AHEAD)):
            if kids[j] is node:
                return j
    index: int = kids.index(node)
    return index


def _splice(parent: Any, i: int, new: list[Any]) -> None:
    """Replace ``parent.childNodes[i]`` (or insert before it when ``i`` is past a removal) by
    ``new``, fixing the sibling links and parent pointers exactly as minidom would."""
    kids = parent.childNodes
    old = kids[i]
    prev = kids[i - 1] if i else None
    nxt = kids[i + 1] if i + 1 < len(kids) else None
    kids[i:i + 1] = new
    for c in new:
        c.parentNode = parent
        c.previousSibling = prev
        if prev is not None:
            prev.nextSibling = c
        prev = c
    if prev is not None:
        prev.nextSibling = nxt
    if nxt is not None:
        nxt.previousSibling = prev
    old.parentNode = None
    old.previousSibling = old.nextSibling = None
    _hints[id(parent)] = (parent, i + len(new))
    if old.nodeType == _ELEMENT or any(c.nodeType == _ELEMENT for c in new):
        minidom._clear_id_cache(parent)  # type: ignore[attr-defined]


def _detach_children(doc: Any) -> list[Any]:
    kids = list(doc.childNodes)
    del doc.childNodes[:]
    for c in kids:
        c.parentNode = None
        c.previousSibling = c.nextSibling = None
    if any(c.nodeType == _ELEMENT for c in kids):
        minidom._clear_id_cache(doc)  # type: ignore[attr-defined]
    return kids


def replace_node(node: Any, by: Any, content_only: bool = False) -> Any:
    parent = node.parentNode
    docs = [] if by is None else (by if isinstance(by, list) else [by])
    fast = parent is not None and parent.nodeType == _ELEMENT
    if fast:
        allowed = parent._child_node_types
        for doc in docs:
            if content_only:
                fast = doc.nodeType == _ELEMENT and all(c.nodeType in allowed for c in doc.childNodes)
            else:
                fast = doc.parentNode is None and doc.nodeType in allowed and doc is not node
            if not fast:
                break
    if not fast:
        return _orig["replace_node"](node, by, content_only)
    new: list[Any] = []
    for doc in docs:
        if content_only:
            new.extend(_detach_children(doc))
        else:
            new.append(doc)
    _splice(parent, _index_of(parent, node), new)
    return None


def _remove_child(parent: Any, child: Any) -> None:
    if parent.nodeType != _ELEMENT:
        parent.removeChild(child)
        return
    _splice(parent, _index_of(parent, child), [])


def _insert_before(parent: Any, new: Any, ref: Any) -> None:
    if parent.nodeType != _ELEMENT or new.nodeType not in parent._child_node_types:
        parent.insertBefore(new, ref)
        return
    if new.parentNode is not None:
        _remove_child(new.parentNode, new)
    i = _index_of(parent, ref)
    kids = parent.childNodes
    prev = kids[i - 1] if i else None
    kids.insert(i, new)
    new.parentNode = parent
    new.previousSibling = prev
    new.nextSibling = ref
    ref.previousSibling = new
    if prev is not None:
        prev.nextSibling = new
    _hints[id(parent)] = (parent, i + 1)


def remove_previous_comments(node: Any) -> None:
    """xacro's ``remove_previous_comments`` with the linear-time edits above."""
    import xacro
    next = node.nextSibling
    previous = node.previousSibling
    while previous:
        if previous.nodeType == _TEXT and previous.data.isspace() and previous.data.count('\n') <= 1:
            previous = previous.previousSibling  # skip a single empty text node (max 1 newline)

        if previous and previous.nodeType == _COMMENT:
            comment = previous
            previous = previous.previousSibling
            _remove_child(node.parentNode, comment)
        else:
            # xacro moves its singleton empty text node here to stop removing comments later
            empty = xacro._empty_text_node
            if next and empty is not next:
                _insert_before(node.parentNode, empty, next)
            return


def install() -> None:
    """Route xacro's module globals (looked up at call time) through the linear versions."""
    import xacro
    if _orig:
        return
    _orig["replace_node"] = xacro.replace_node
    _orig["remove_previous_comments"] = xacro.remove_previous_comments
    xacro.replace_node = replace_node
    xacro.remove_previous_comments = remove_previous_comments
