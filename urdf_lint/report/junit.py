"""``junit``: JUnit XML, one failed test case per finding and one passed case per clean model."""
from __future__ import annotations

from urdf_lint.core.locations import display_path
from urdf_lint.report.base import (BaseFormatter, Outcome, chain_text, fold_instances, grouped,
                                   message, related_text, value_from_text)
from urdf_lint.core.escape import escape_xml


class JunitFormatter(BaseFormatter):
    name = "junit"
    help = "JUnit XML for CI test reports"

    def write(self, result: Outcome) -> None:
        result = grouped(result)
        def quoteattr(s: str) -> str:
            return '"' + escape_xml(s) + '"'

        escape = escape_xml  # one line per part: a name cannot add lines to a CI log
        cases = []
        for f in result.findings:
            name = f"{f.code} {display_path(f.file)}:{f.line}:{f.col}"
            body = escape(f"{display_path(f.file)}:{f.line}:{f.col}: {f.code} {message(f)}") \
                + "".join("\n" + escape(x) for x in (chain_text(f), value_from_text(f), related_text(f),
                                                      fold_instances(f)) if x)
            tag = "failure"
            cases.append(f'    <testcase classname={quoteattr("urdf-lint." + f.code)} name={quoteattr(name)}>'
                         f'<{tag} type={quoteattr(f.severity)} message={quoteattr(message(f))}>'
                         f'{body}</{tag}></testcase>')
        for m in result.models:
            if not any(m.label in f.models for f in result.findings):
                cases.append(f'    <testcase classname="urdf-lint.model" name={quoteattr(m.label)}/>')
        w = self.stream.write
        w('<?xml version="1.0" encoding="UTF-8"?>\n')
        failures = len(result.findings)
        w(f'<testsuites name="urdf-lint" tests="{len(cases)}" failures={quoteattr(str(failures))}>\n')
        w(f'  <testsuite name="urdf-lint" tests="{len(cases)}" failures="{failures}" errors="0">\n')
        w("\n".join(cases) + ("\n" if cases else ""))
        w("  </testsuite>\n</testsuites>\n")
