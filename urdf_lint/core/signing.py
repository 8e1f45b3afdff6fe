"""The signature of an entry urdf-lint keeps in a cache (the result cache,
:mod:`urdf_lint.run.cache`, and the mesh-facts store, :mod:`urdf_lint.meshes.store`): HMAC-SHA256
with the user's key over the entry's file name and its bytes, so an entry written by anyone
without the key, or copied under another name (another key, another content digest), is no
entry. The stored form is the signature's line, then the bytes."""
from __future__ import annotations

import hashlib
import hmac


def mac(secret: bytes, name: str, blob: bytes) -> bytes:
    """The signature (hex, ASCII) of ``blob`` stored under the file name ``name``."""
    signed = name.encode() + b"\0" + blob
    return hmac.new(secret, signed, hashlib.sha256).hexdigest().encode("ascii")


def signed(secret: bytes, name: str, blob: bytes) -> bytes:
    """What is written for ``blob`` under ``name``: its signature's line, then the bytes."""
    return mac(secret, name, blob) + b"\n" + blob


def verified(secret: bytes, name: str, data: bytes) -> bytes | None:
    """The bytes of a stored entry (:func:`signed`) if ``secret`` signed them under ``name``."""
    sig, _, blob = data.partition(b"\n")
    return blob if hmac.compare_digest(sig, mac(secret, name, blob)) else None


def derive(secret: bytes, purpose: str) -> bytes:
    """A key of its own for one use of the user's key (the mesh-facts store's: a process that
    holds it can check facts entries, not sign result-cache entries)."""
    return hmac.new(secret, b"urdf-lint key for " + purpose.encode(), hashlib.sha256).digest()
