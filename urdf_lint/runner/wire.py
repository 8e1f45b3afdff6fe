"""The encoding of what a worker sends back: plain data (JSON), not pickle.

A pickle is a program: what it may call depends on how each Python release pickles an object
(Python 3.11.2, Debian 12's, pickles an enum member as a call of ``builtins.getattr``, which an
allow-list of classes refuses), and an end that reads pickles from an untrusted process must
guess which calls are harmless. This encoding names no function. A message is a JSON document
of plain values (str, int, float, bool, None, lists, dicts with str keys) in which everything
else is an object tagged with ``TAG``:

* ``{"~": "t", "v": [..]}``: a tuple (``"s"``: a set, ``"fs"``: a frozenset);
* ``{"~": "m", "v": [[k, v], ..]}``: a dict whose keys are not all str (or that holds ``TAG``);
* ``{"~": "b", "i": n}``: bytes, attachment ``n`` (raw, after the JSON);
* ``{"~": "a", "d": dtype, "s": shape, "i": n}``: a numpy array of numbers, attachment ``n``;
* ``{"~": "e", "c": name, "v": value}``: an enum member (looked up by its value);
* ``{"~": "n", "c": name, "v": [..]}``: a named tuple (its fields in order);
* ``{"~": "d", "c": name, "f": {field: value}}``: a dataclass, every field by name.

``name`` is ``module:qualname``. The reading end accepts a class only when ``(module, name)``
is in its allow-list (and is that kind of class): anything else is :class:`Refused` with the
name, before any module is imported. A dataclass is rebuilt without its ``__init__`` (as
pickle does: its fields are set), an enum member or named tuple from its values; no function
a message names is ever called. The layout is fixed here, so both ends agree across patch releases.

The bytes: ``MAGIC``, the JSON's length and the number of attachments (``!II``), each
attachment's length (``!Q``), the JSON (ASCII), then the attachments.
"""
from __future__ import annotations

import dataclasses
import enum
import json
import struct
from typing import Any, Callable

TAG = "~"
MAGIC = b"ULw1"
_HEAD = struct.Struct("!II")
_BLOB = struct.Struct("!Q")
_json_out = json.JSONEncoder(separators=(",", ":"), check_circular=False).encode
_PLAIN = frozenset({str, int, float, bool, type(None)})   # as JSON has them


class Refused(ValueError):
    """A message the reading end does not accept (a class not allowed, an unreadable one)."""


class Unencodable(TypeError):
    """A value the encoding has no form for (an object of a class that is no dataclass,
    enum or named tuple)."""


# -- encoding -----------------------------------------------------------------------------------
def encode(value: Any) -> bytes:
    """``value`` as a message."""
    blobs: list[bytes] = []
    text = _json_out(_Encoder(blobs).enc(value)).encode("ascii")
    return b"".join([MAGIC, _HEAD.pack(len(text), len(blobs)),
                     *(_BLOB.pack(len(b)) for b in blobs), text, *blobs])


def _name(cls: type) -> str:
    return f"{cls.__module__}:{cls.__qualname__}"


class _Encoder:
    def __init__(self, blobs: list[bytes]):
        self.blobs = blobs
        self.by_type: dict[type, Callable[[Any], Any]] = {
            list: self.seq, tuple: self.tagged("t"), set: self.tagged("s"),
            frozenset: self.tagged("fs"), dict: self.mapping, bytes: self.raw,
            bytearray: self.raw}

    def enc(self, x: Any) -> Any:
        t = type(x)
        if t in _PLAIN:
            return x
        f = self.by_type.get(t) or self.by_type.setdefault(t, self.for_class(t))
        return f(x)

    def seq(self, x: Any) -> list[Any]:
        enc = self.enc
        return [v if type(v) in _PLAIN else enc(v) for v in x]

    def tagged(self, tag: str) -> Callable[[Any], Any]:
        return lambda x: {TAG: tag, "v": self.seq(x)}

    def mapping(self, x: dict[Any, Any]) -> Any:
        enc = self.enc
        if TAG not in x and all(type(k) is str for k in x):
            return {k: v if type(v) in _PLAIN else enc(v) for k, v in x.items()}
        return {TAG: "m", "v": [[enc(k), enc(v)] for k, v in x.items()]}

    def attach(self, b: bytes) -> int:
        self.blobs.append(b)
        return len(self.blobs) - 1

    def raw(self, x: Any) -> Any:
        return {TAG: "b", "i": self.attach(bytes(x))}

    def for_class(self, t: type) -> Callable[[Any], Any]:
        name = _name(t)
        if issubclass(t, enum.Enum):
            return lambda x: {TAG: "e", "c": name, "v": self.enc(x.value)}
        if issubclass(t, tuple) and hasattr(t, "_fields"):
            return lambda x: {TAG: "n", "c": name, "v": self.seq(x)}
        if dataclasses.is_dataclass(t):
            names = tuple(f.name for f in dataclasses.fields(t))
            return lambda x: {TAG: "d", "c": name, "f": self.mapping(
                {n: getattr(x, n) for n in names})}
        if t.__module__ == "numpy" and t.__name__ == "ndarray":
            return self.array
        raise Unencodable(f"no plain-data form for a {t.__module__}.{t.__qualname__}")

    def array(self, x: Any) -> Any:
        if x.dtype.hasobject or x.dtype.fields is not None:
            raise Unencodable(f"no plain-data form for an array of {x.dtype}")
        import numpy as np
        return {TAG: "a", "d": x.dtype.str, "s": list(x.shape),
                "i": self.attach(np.ascontiguousarray(x).tobytes())}


# -- decoding -----------------------------------------------------------------------------------
def decode(data: bytes | bytearray, allowed: frozenset[tuple[str, str]]) -> Any:
    """The value of message ``data``, made only of plain data and the classes ``allowed``
    (``(module, name)`` pairs; numpy arrays: ``("numpy", "ndarray")``); anything else, or a
    message that is not one, is :class:`Refused`."""
    view = memoryview(data)
    at = len(MAGIC) + _HEAD.size
    if len(view) < at or bytes(view[:len(MAGIC)]) != MAGIC:
        raise Refused("not a message of this encoding")
    n, count = _HEAD.unpack(view[len(MAGIC):at])
    if at + count * _BLOB.size + n > len(view):
        raise Refused("a message shorter than it says")
    lengths = [_BLOB.unpack(view[at + k * _BLOB.size:at + (k + 1) * _BLOB.size])[0]
               for k in range(count)]
    text = at + count * _BLOB.size
    offsets, at = [], text + n
    for k in lengths:
        offsets.append((at, at + k))
        at += k
    if at != len(view):
        raise Refused("attachments that do not add up to the message")
    try:
        return json.loads(bytes(view[text:text + n]),
                          object_hook=_Decoder(view, offsets, allowed).hook)
    except Refused:
        raise
    except (ValueError, TypeError, KeyError, IndexError, AttributeError, RecursionError,
            MemoryError, OverflowError) as e:
        raise Refused(f"an unreadable message ({type(e).__name__})") from e


_KINDS = {"e": "an enum", "n": "a named tuple", "d": "a dataclass"}


class _Decoder:
    def __init__(self, view: memoryview, offsets: list[tuple[int, int]],
                 allowed: frozenset[tuple[str, str]]):
        self.view, self.offsets, self.allowed = view, offsets, allowed
        self.classes: dict[str, type] = {}

    def hook(self, d: dict[str, Any]) -> Any:
        tag = d.get(TAG)
        if tag is None:
            return d
        if tag == "t":
            return tuple(d["v"])
        if tag == "m":
            return {k: v for k, v in d["v"]}
        if tag == "s":
            return set(d["v"])
        if tag == "fs":
            return frozenset(d["v"])
        if tag == "b":
            start, end = self.offsets[d["i"]]
            return bytes(self.view[start:end])
        if tag == "a":
            return self.array(d)
        if tag in _KINDS:
            return self.instance(tag, d)
        raise Refused(f"an unreadable message (tag {str(tag)[:40]!r})")

    def cls(self, tag: str, name: Any) -> type:
        got = self.classes.get(name)
        if got is not None:
            return got
        module, _, qualname = str(name).partition(":")
        if (module, qualname) not in self.allowed:
            raise Refused(f"{module}.{qualname}"[:200])
        import importlib
        cls = getattr(importlib.import_module(module), qualname, None)
        ok = isinstance(cls, type) and (
            issubclass(cls, enum.Enum) if tag == "e" else
            issubclass(cls, tuple) and hasattr(cls, "_fields") if tag == "n" else
            dataclasses.is_dataclass(cls))
        if not ok:
            raise Refused(f"{module}.{qualname} (not {_KINDS[tag]})")
        assert isinstance(cls, type)
        self.classes[name] = cls
        return cls

    def instance(self, tag: str, d: dict[str, Any]) -> Any:
        cls = self.cls(tag, d["c"])
        if tag == "e":
            return cls(d["v"])
        if tag == "n":
            v = d["v"]
            if type(v) is not list or len(v) != len(cls._fields):   # type: ignore[attr-defined]
                raise Refused(f"{d['c']} with {len(v)} fields")
            return tuple.__new__(cls, v)
        fields = d["f"]
        if type(fields) is not dict or fields.keys() != _field_names(cls):
            raise Refused(f"{d['c']} with other fields than its own")
        obj: Any = object.__new__(cls)
        obj.__dict__.update(fields)
        return obj

    def array(self, d: dict[str, Any]) -> Any:
        if ("numpy", "ndarray") not in self.allowed:
            raise Refused("numpy.ndarray")
        import numpy as np
        dtype = np.dtype(str(d["d"]))
        if dtype.hasobject or dtype.fields is not None:
            raise Refused(f"an array of {dtype}")
        start, end = self.offsets[d["i"]]
        return np.frombuffer(self.view[start:end], dtype).reshape(
            [int(k) for k in d["s"]])


_NAMES: dict[type, frozenset[str]] = {}


def _field_names(cls: type) -> frozenset[str]:
    names = _NAMES.get(cls)
    if names is None:
        names = _NAMES[cls] = frozenset(f.name for f in dataclasses.fields(cls))
    return names
