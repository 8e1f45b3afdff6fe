"""Compare two urdf-lint JSON reports: per code, findings and distinct source locations, and
whether every old (file, line, code) is still reported (as a finding or an instance; an old
UL401/UL407 about an unknown package counts as found when a UL004 lists that place)."""
import collections
import json
import sys


def places(doc):
    out = set()
    for f in doc["findings"]:
        for i in f.get("instances") or [f]:
            out.add((i["file"], i["line"], f["code"]))
    return out


def table(doc):
    n = collections.Counter(f["code"] for f in doc["findings"])
    locs = collections.defaultdict(set)
    inst = collections.Counter()
    for f in doc["findings"]:
        for i in f.get("instances") or [f]:
            locs[f["code"]].add((i["file"], i["line"]))
        inst[f["code"]] += f.get("count", 1)
    return n, locs, inst


old, new = (json.load(open(p)) for p in sys.argv[1:3])
n0, l0, _ = table(old)
n1, l1, i1 = table(new)
print(f"{'code':6} {'before':>7} {'locs':>5} | {'after':>6} {'locs':>5} {'instances':>9}")
for c in sorted(set(n0) | set(n1)):
    print(f"{c:6} {n0[c]:7} {len(l0[c]):5} | {n1[c]:6} {len(l1[c]):5} {i1[c]:9}")
print(f"{'total':6} {sum(n0.values()):7} {sum(len(v) for v in l0.values()):5} | "
      f"{sum(n1.values()):6} {sum(len(v) for v in l1.values()):5} {sum(i1.values()):9}")
now = places(new)
said = {(f["code"], i["message"]) for f in new["findings"] for i in f.get("instances") or [f]}
lost, moved = [], []
for f in old["findings"]:
    k = (f["file"], f["line"], f["code"])
    if k in now:
        continue
    if f["code"] in ("UL401", "UL407") and "unknown package" in f["message"] \
            and (f["file"], f["line"], "UL004") in now:
        continue
    if f["file"].endswith(".urdf") and (f["code"], f["message"]) in said:
        # a generated URDF identical to today's expansion: the same finding at the xacro line
        moved.append(k)
        continue
    lost.append((k, f["message"][:120]))
print(f"old findings of generated URDFs now reported (same code and message) at their xacro: "
      f"{len(moved)} (in {len({k[0] for k in moved})} URDF files)")
print(f"old source locations not reported any more: {len(lost)}")
for k, m in lost:
    print("  LOST", *k, m)
