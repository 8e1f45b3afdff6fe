"""What a worker sends back crosses the pipe as plain data (urdf_lint/runner/wire.py), never a
pickle: the parent's reading depends neither on how one Python patch release pickles an object
(Debian 12's 3.11.2 pickles an enum member as a call of ``builtins.getattr``: issue 31) nor on
an allow-list of callables. See SECURITY.md, "Every distribution Python: the worker channel"."""
from __future__ import annotations

import dataclasses
import enum
import json
import math
import os
import pickle
import re
import shutil
from typing import NamedTuple

import pytest

from conftest import REPO, run_main
from urdf_lint.runner import forked, wire


class Colour(str, enum.Enum):
    RED = "red"


class Point(NamedTuple):
    x: int
    y: float
    tag: tuple = ()


@dataclasses.dataclass(frozen=True)
class Box:
    name: str
    corner: Point
    extra: object = None


HERE = __name__
ALLOWED = frozenset({(HERE, "Colour"), (HERE, "Point"), (HERE, "Box")})


def _message(value_json: str, blobs: tuple = ()) -> bytes:
    """A message written by hand, as a worker that no longer keeps to the protocol could."""
    text = value_json.encode()
    return b"".join([wire.MAGIC, wire._HEAD.pack(len(text), len(blobs)),
                     *(wire._BLOB.pack(len(b)) for b in blobs), text, *blobs])


def test_plain_data_round_trips_with_its_types():
    value = {"t": (1, "a", (2.5, None)), "s": {1, 2}, "fs": frozenset({"x"}), "b": b"\x80\x05\0",
             "ba": [True, False, -0.0, 2 ** 70, math.inf], "keys": {(1, 2): "tuple key", 3: "int"},
             "~": "a key that is the tag", "bad utf-8 path": "/x/\udcff.xacro",
             "obj": Box("b", Point(1, 2.0, ("t",)), extra=[Colour.RED, {"~": 1}])}
    data = wire.encode(value)
    back = wire.decode(bytearray(data), ALLOWED)
    assert back == value
    assert type(back["t"]) is tuple and type(back["t"][1]) is str and type(back["s"]) is set
    assert type(back["fs"]) is frozenset and type(back["b"]) is bytes
    assert type(back["obj"]) is Box and type(back["obj"].corner) is Point
    assert back["obj"].extra[0] is Colour.RED
    assert math.isnan(wire.decode(wire.encode(math.nan), frozenset()))


def test_numpy_arrays_cross_as_attachments():
    np = pytest.importorskip("numpy")
    a = np.arange(12, dtype="<f4").reshape(3, 4)[:, ::2]       # not contiguous
    back = wire.decode(bytearray(wire.encode({"a": a, "i": np.zeros((0, 2, 3), dtype=np.uint8)})),
                       frozenset({("numpy", "ndarray")}))
    assert back["a"].dtype == a.dtype and (back["a"] == a).all() and back["a"].shape == (3, 2)
    assert back["i"].shape == (0, 2, 3)
    with pytest.raises(wire.Refused, match="numpy.ndarray"):     # arrays only where allowed
        wire.decode(wire.encode(a), frozenset())
    with pytest.raises(wire.Unencodable):
        wire.encode(np.array([object()]))
    forged = _message('{"~":"a","d":"|O","s":[1],"i":0}', (b"\0" * 8,))
    with pytest.raises(wire.Refused, match="object"):
        wire.decode(forged, frozenset({("numpy", "ndarray")}))


def test_an_object_of_no_known_form_is_not_sent():
    class Other:
        pass
    with pytest.raises(wire.Unencodable, match="Other"):
        wire.encode({"x": [Other()]})


@pytest.mark.parametrize("forged, why", [
    ('{"~":"e","c":"os:system","v":"touch /tmp/pwned"}', "os.system"),
    ('{"~":"d","c":"builtins:getattr","f":{}}', "builtins.getattr"),
    ('{"~":"n","c":"subprocess:Popen","v":[["id"]]}', "subprocess.Popen"),
    ('{"~":"e","c":"this:s","v":1}', "this.s"),     # (``this`` prints when imported)
    (f'{{"~":"e","c":"{HERE}:Box","v":1}}', "not an enum"),
    (f'{{"~":"d","c":"{HERE}:Box","f":{{"name":"b"}}}}', "other fields"),
    (f'{{"~":"d","c":"{HERE}:Box","f":{{"name":"b","corner":1,"extra":2,"x":3}}}}',
     "other fields"),
    (f'{{"~":"n","c":"{HERE}:Point","v":[1]}}', "1 fields"),
    ('{"~":"zz","v":1}', "tag 'zz'"),
    ('{"~":"m","v":[[[1],2]]}', "unreadable"),
    ('[1, 2', "unreadable"),
])
def test_a_forged_message_is_refused_by_name_and_nothing_is_imported(forged, why):
    import sys
    before = set(sys.modules)
    with pytest.raises(wire.Refused, match=re.escape(why)):
        wire.decode(_message(forged), ALLOWED)
    assert set(sys.modules) - before == set() and "this" not in sys.modules


@pytest.mark.parametrize("data", [b"", b"\x80\x05N.", wire.MAGIC + b"\0\0\0\x09\0\0\0\0[]",
                                  _message("[]") + b"x", _message("[]", (b"ab",))[:-1]])
def test_what_is_not_a_whole_message_is_refused(data):
    with pytest.raises(wire.Refused):
        wire.decode(data, ALLOWED)


def _demo(tmp_path):
    shutil.copytree(REPO / "descriptions", tmp_path / "demo")
    readme = (REPO / "README.md").read_text().replace("\n", " ")
    want = re.search(r"`(Found \d+ problem\(s\) \([^)]*\) in \d+ model\(s\)\.)`", readme)
    assert want, "README.md's demo summary line not found"
    return want.group(1)


def test_the_worker_sends_plain_data_and_the_parent_reads_no_pickle(tmp_path, monkeypatch):
    """The demo linted for real: every message the parent reads from a worker is this
    encoding (JSON, no attachment, no pickle opcode), and the parent never unpickles."""
    want = _demo(tmp_path)
    parent = os.getpid()
    read: list = []
    real_read = forked.Conn._read

    def spy(self, n, deadline=None):
        buf = real_read(self, n, deadline)
        if os.getpid() == parent:
            read.append(bytes(buf))
        return buf

    def no_pickle(real):
        def refuse(*a, **k):
            if os.getpid() == parent:
                raise AssertionError("the parent unpickled a worker's message")
            return real(*a, **k)
        return refuse
    monkeypatch.setattr(forked.Conn, "_read", spy)
    for name in ("loads", "load", "Unpickler"):
        monkeypatch.setattr(pickle, name, no_pickle(getattr(pickle, name)))
    p = run_main("check", "demo", "--no-cache", "-j", "2", cwd=tmp_path)
    assert p.returncode == 1 and p.stdout.splitlines()[-1] == want, p.stderr
    bodies = read[1::2]                           # (a header, then its message)
    assert len(bodies) >= 30
    for body in bodies:
        # (pickle's PROTO opcode, 0x80, may be a byte of the binary length; not of the JSON)
        assert body.startswith(wire.MAGIC) and b"\x80" not in body[12:], body[:40]
        n, blobs = wire._HEAD.unpack(body[4:12])
        assert blobs == 0 and len(body) == 12 + n
        report = json.loads(body[12:])             # plain JSON: no hook needed to read it
        assert report["~"] == "d" and report["c"] == "urdf_lint.core.jobs:ModelReport"


def test_a_release_that_pickles_enums_by_getattr_lints_the_demo(tmp_path, monkeypatch):
    """Issue 31: Python 3.11.2 (Debian 12) pickles an enum member as ``getattr(Status,
    'MODEL')``; the allow-list of the pickle channel refused every result. Made to pickle that
    way here, the workers' results still arrive: nothing of theirs is pickled."""
    from urdf_lint.core.jobs import Status
    want = _demo(tmp_path)
    monkeypatch.setattr(Status, "__reduce_ex__", lambda self, proto: (getattr, (Status, self.name)),
                        raising=False)
    assert pickle.dumps(Status.MODEL).count(b"getattr") == 1
    p = run_main("check", "demo", "--no-cache", cwd=tmp_path)
    assert "internal error" not in p.stderr, p.stderr
    assert p.returncode == 1 and p.stdout.splitlines()[-1] == want
