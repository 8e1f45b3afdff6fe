"""Expansion scaling: a flat robot of N macro calls and a D-deep recursive macro.

Stock xacro replaces nodes one sibling scan at a time (quadratic); urdf-lint splices
(`urdf_lint/expansion/splice.py`). Each side runs in its own fresh process, with the same raised recursion
limit and thread stack (stock xacro's default limit stops well before depth 400), and the outputs
must be byte-identical.

    .venv/bin/python bench/bench_scaling.py [--links 5000] [--depth 400]
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def flat_robot(n: int) -> str:
    calls = "\n".join(f'  <xacro:seg i="{i}"/>' for i in range(1, n + 1))
    return f"""<?xml version="1.0"?>
<robot name="flat" {X}>
  <xacro:macro name="seg" params="i">
    <!-- one segment -->
    <link name="l${{i}}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
    <joint name="j${{i}}" type="fixed"><parent link="l${{i-1}}"/><child link="l${{i}}"/></joint>
  </xacro:macro>
  <link name="l0"/>
{calls}
</robot>
"""


def deep_robot(d: int) -> str:
    return f"""<?xml version="1.0"?>
<robot name="deep" {X}>
  <xacro:macro name="chain" params="i">
    <link name="l${{i}}"/>
    <xacro:if value="${{i &lt; {d}}}">
      <joint name="j${{i}}" type="fixed"><parent link="l${{i}}"/><child link="l${{i+1}}"/></joint>
      <xacro:chain i="${{i+1}}"/>
    </xacro:if>
  </xacro:macro>
  <xacro:chain i="0"/>
</robot>
"""


RUNNER = r"""
import sys, threading, time
sys.setrecursionlimit(200000)
threading.stack_size(512 * 1024 * 1024)
mode, path, out = sys.argv[1:4]
result = {}
def run():
    t = time.perf_counter()
    if mode == "stock":
        import xacro
        text = xacro.process_file(path).toprettyxml(indent="  ")
    else:
        from urdf_lint.expansion import expand_file
        r = expand_file(path)
        if r.error:
            raise SystemExit(str(r.error))
        text = r.xml
    result["t"] = time.perf_counter() - t
    open(out, "w").write(text)
th = threading.Thread(target=run); th.start(); th.join()
print(result["t"])
"""


def run(mode: str, path: str, out: str) -> tuple[float, float]:
    t = time.perf_counter()
    p = subprocess.run([sys.executable, "-c", RUNNER, mode, path, out], capture_output=True,
                       text=True, check=True)
    return float(p.stdout.strip().splitlines()[-1]), time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--links", type=int, default=5000)
    ap.add_argument("--depth", type=int, default=400)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "p", "urdf"))
        with open(os.path.join(d, "p", "package.xml"), "w") as f:
            f.write("<package><name>p</name></package>")
        print(f"{'case':<16}{'stock s':>10}{'urdf-lint s':>13}{'ratio':>8}  identical")
        for name, text in ((f"flat {a.links}", flat_robot(a.links)),
                           (f"deep {a.depth}", deep_robot(a.depth))):
            path = os.path.join(d, "p", "urdf", name.replace(" ", "_") + ".urdf.xacro")
            with open(path, "w") as f:
                f.write(text)
            s_in, _ = run("stock", path, path + ".stock")
            u_in, _ = run("urdf-lint", path, path + ".ours")
            same = open(path + ".stock", "rb").read() == open(path + ".ours", "rb").read()
            print(f"{name:<16}{s_in:>10.2f}{u_in:>13.2f}{u_in / s_in:>8.3f}  {same}")


if __name__ == "__main__":
    main()
