"""Findings: what the rules and the expansion report."""
from __future__ import annotations

from dataclasses import dataclass, field

SEVERITIES = ("info", "warning", "error")
SEVERITY_RANK = {s: i for i, s in enumerate(SEVERITIES)}


@dataclass
class Finding:
    code: str
    name: str
    severity: str
    message: str
    file: str
    line: int
    col: int
    chain: tuple = ()
    models: list = field(default_factory=list)   # display ids of the models it was found in

    def key(self):
        return (self.file, self.line, self.col, self.code, self.message)

    def to_dict(self) -> dict:
        return {"code": self.code, "name": self.name, "severity": self.severity,
                "message": self.message, "file": self.file, "line": self.line, "col": self.col,
                "chain": [list(c) for c in self.chain], "models": list(self.models)}

    @classmethod
    def from_dict(cls, d: dict) -> "Finding":
        return cls(code=d["code"], name=d.get("name", ""), severity=d.get("severity", "error"),
                   message=d["message"], file=d["file"], line=int(d["line"]), col=int(d["col"]),
                   chain=tuple(tuple(c) for c in d.get("chain", ())),
                   models=list(d.get("models", [])))


def merge(findings: list[Finding]) -> list[Finding]:
    """One finding per source location and message; the models that share it are listed."""
    out: dict = {}
    for f in findings:
        k = f.key()
        if k in out:
            for m in f.models:
                if m not in out[k].models:
                    out[k].models.append(m)
        else:
            out[k] = f
    return sorted(out.values(), key=lambda f: (f.file, f.line, f.col, f.code, f.message))
