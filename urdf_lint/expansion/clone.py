"""A macro body cloned at a fraction of minidom's cost, checked equal to minidom's clone.

xacro instantiates a macro by ``m.body.cloneNode(deep=True)`` and expands the copy. minidom
builds that copy through its public DOM calls (``createElementNS``, ``setAttributeNS``,
``getAttributeNodeNS``, ``appendChild``) and a user-data callback per node; on real robots the
copies are about a seventh of a worker's CPU. :func:`clone_tree` builds the same nodes
directly: the same classes with the same fields, the same attribute maps in the same order,
the same sibling links, and the user data each node's handler gives its clone (the
expansion's source stamps through ``handler.cloned``, any other through ``handler.handle``,
as minidom calls it).

It relies on minidom's node fields, which have not changed from Python 3.10 to 3.13. So that a
Python whose minidom differs can never get a different tree, :func:`usable` clones a sample
both ways once per process and compares every field (:func:`same_tree`); when they differ the
expansion keeps minidom's ``cloneNode``. Only macro bodies get the fast clone (:class:`MacroBody`,
set by the ``grab_macro`` hook); nothing of minidom or xacro is changed.
"""
from __future__ import annotations

import xml.dom
from typing import Any, Callable
from xml.dom import minidom

_ELEMENT, _TEXT = xml.dom.Node.ELEMENT_NODE, xml.dom.Node.TEXT_NODE
_CLONED = xml.dom.UserDataHandler.NODE_CLONED
# (minidom's classes, used through their fields: untyped for mypy, whose stubs name few)
_Element: Any = minidom.Element
_Text: Any = minidom.Text
_Attr: Any = minidom.Attr
_NodeList: Any = minidom.NodeList  # type: ignore[attr-defined]


def clone_tree(node: Any, doc: Any, parent: Any = None,
               restamp: Callable[[Any], Any] | None = None) -> Any:
    """A deep copy of ``node`` owned by ``doc`` under ``parent``: what minidom's
    ``_clone_node(node, True, doc)`` gives (with ``parentNode`` set as ``appendChild`` sets
    it). Elements and text are built here; any other node (comments, CDATA, processing
    instructions) is cloned by minidom.

    ``restamp``: a copy of a parsed document standing for a new parse of it
    (:func:`copy_document`): each user datum a handler would clone is ``restamp(value)``,
    and the other nodes are owned by ``doc`` too, as the parser makes them."""
    kind = node.nodeType
    c: Any
    if kind == _ELEMENT:
        c = _Element.__new__(_Element)
        c.ownerDocument = doc
        c.parentNode = parent
        c.tagName = c.nodeName = node.tagName
        c.prefix = node.prefix
        c.namespaceURI = node.namespaceURI     # (no _localName: createElementNS sets none)
        if restamp is not None and hasattr(node, "_localName"):
            c._localName = node._localName     # (the parser sets one)
        c.nextSibling = c.previousSibling = None
        src = node._attrs
        if src:
            attrs, attrs_ns = {}, {}
            for name, a in src.items():
                n = _Attr.__new__(_Attr)
                n.ownerElement = c
                n.ownerDocument = doc
                n._name = a._name
                n.namespaceURI = a.namespaceURI
                n._prefix = a._prefix
                n._localName = a.localName
                value = a._value
                t = _Text.__new__(_Text)
                t.ownerDocument = t.parentNode = t.previousSibling = t.nextSibling = None
                t._data = value
                kids = _NodeList()
                kids.append(t)
                n.childNodes = kids
                n._value = value
                n.specified = a.specified
                attrs[name] = n
                attrs_ns[(n.namespaceURI, n._localName)] = n
            c._attrs, c._attrsNS = attrs, attrs_ns
        else:
            c._attrs = c._attrsNS = None
        children = _NodeList()
        prev = None
        for child in node.childNodes:
            k = clone_tree(child, doc, c, restamp)
            k.previousSibling = prev
            if prev is not None:
                prev.nextSibling = k
            children.append(k)
            prev = k
        c.childNodes = children
    elif kind == _TEXT:
        c = _Text.__new__(_Text)
        c.ownerDocument = doc
        c.parentNode = parent
        c.previousSibling = c.nextSibling = None
        c._data = node._data
    else:                  # (minidom calls its user data handlers)
        c = node.cloneNode(True)
        c.parentNode = parent
        if restamp is not None:
            c.ownerDocument = doc
        return c
    data = getattr(node, "_user_data", None)
    if data:
        for key, (value, handler) in list(data.items()):
            if handler is None:
                continue
            cloned = getattr(handler, "cloned", None)
            if cloned is not None and restamp is not None:
                cloned = restamp
            if cloned is not None:      # the expansion's stamps: the clone's stamp, set
                mine = getattr(c, "_user_data", None)
                if mine is None:
                    c._user_data = mine = {}
                mine[key] = (cloned(value), handler)
            else:
                handler.handle(_CLONED, key, value, node, c)
    return c


def copy_document(src: Any, restamp: Callable[[Any], Any]) -> Any:
    """A new document equal to ``src`` (a parsed document without a DOCTYPE) in everything a
    new parse of the same bytes gives: its XML declaration, its nodes (:func:`clone_tree`)
    and their user data, ``restamp(value)`` where a handler would clone it."""
    doc = minidom.getDOMImplementation().createDocument(None, None, None)
    doc.version, doc.encoding, doc.standalone = src.version, src.encoding, src.standalone
    for child in src.childNodes:
        doc.appendChild(clone_tree(child, doc, None, restamp))
    return doc


class MacroBody(minidom.Element):
    """A macro's body element (xacro's ``Macro.body``): ``cloneNode(deep=True)`` is
    :func:`clone_tree`. Its copies are plain minidom elements."""
    __slots__ = ()

    def cloneNode(self, deep: bool) -> Any:
        if not deep:
            return super().cloneNode(deep)
        return clone_tree(self, self.ownerDocument or self)


_FIELDS = ("nodeType", "nodeName", "prefix", "namespaceURI", "localName", "nodeValue")
_ATTR_FIELDS = ("name", "value", "namespaceURI", "prefix", "localName", "specified")


def same_tree(a: Any, b: Any) -> bool:
    """Whether two minidom trees are alike in everything a reader of them sees: classes,
    names, namespaces, values, attributes (in order, by name and by namespace, with their
    owners and text), user data, owner documents, and parent and sibling links."""
    if type(a) is not type(b) or any(getattr(a, f, None) != getattr(b, f, None) for f in _FIELDS):
        return False
    if a.ownerDocument is not b.ownerDocument or \
            getattr(a, "_user_data", None) != getattr(b, "_user_data", None):
        return False
    if getattr(a, "_localName", None) != getattr(b, "_localName", None):
        return False          # (a local name kept apart from the tag: a renamed clone's)
    if a.nodeType == _ELEMENT and not _same_attributes(a, b):
        return False
    return _same_children(a, b)


def _same_attributes(a: Any, b: Any) -> bool:
    x, y = a._attrs or {}, b._attrs or {}
    if list(x) != list(y) or list(a._attrsNS or {}) != list(b._attrsNS or {}):
        return False
    for p, q in zip(x.values(), y.values(), strict=True):
        if type(p) is not type(q) or any(getattr(p, f) != getattr(q, f) for f in _ATTR_FIELDS):
            return False
        if p.ownerElement is not a or q.ownerElement is not b or \
                p.ownerDocument is not q.ownerDocument:
            return False
        if [(type(t), t.data) for t in p.childNodes] != [(type(t), t.data) for t in q.childNodes]:
            return False
        if (b._attrsNS or {}).get((q.namespaceURI, q.localName)) is not q:
            return False
    return True


def _same_children(a: Any, b: Any) -> bool:
    ka, kb = list(a.childNodes), list(b.childNodes)
    if len(ka) != len(kb):
        return False
    for i, (p, q) in enumerate(zip(ka, kb, strict=True)):
        if q.parentNode is not b or p.parentNode is not a:
            return False
        if q.previousSibling is not (kb[i - 1] if i else None) or \
                q.nextSibling is not (kb[i + 1] if i + 1 < len(kb) else None):
            return False
        if not same_tree(p, q):
            return False
    return True


_usable: bool | None = None


def usable(sample: Any) -> bool:
    """Whether :func:`clone_tree` gives minidom's clone on this Python: checked once per
    process on ``sample`` (an element of a parsed document, with the expansion's stamps)."""
    global _usable
    if _usable is None:
        try:
            doc = sample.ownerDocument
            _usable = same_tree(_Element.cloneNode(sample, True), clone_tree(sample, doc))
        except Exception:  # noqa: BLE001 - any surprise: minidom's clone, as before
            _usable = False
    return _usable
