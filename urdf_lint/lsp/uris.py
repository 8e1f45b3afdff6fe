"""File URIs of the protocol and the real paths the server works with."""
from __future__ import annotations

import os
from pathlib import Path
from urllib.parse import unquote, urlparse


def uri_path(uri: str) -> str:
    return os.path.realpath(unquote(urlparse(uri).path))


def path_uri(path: str) -> str:
    return Path(path).as_uri()
