"""Independent checks of the IEC 61131-3 export (run by `cargo xtask iec`).

Every `.st` file is parsed by blark (a Structured Text parser written by
others); every `.xml` file is validated against the PLCopen TC6 XML v2.01
schema with xmlschema, and the ST body of each of its POUs is parsed by
blark as a statement list. Any error fails the run.

blark's grammar (iec.lark) is used with one alternative removed:
`bare_array_initialization`, TwinCAT's initialiser list without brackets.
IEC 61131-3 requires the brackets, and with that alternative a bracketed
list of n elements has as many parses as there are ways to bracket it, so
the Earley parser's time grows as n^3 (400 elements: about 4 minutes) and
a supervisor's transition array would never finish. Removing an
alternative only shrinks the language: whatever parses here also parses
with blark as published.

usage: iec_check.py --xsd FILE --xsd-sha256 HEX [--jobs N] [--max-st-bytes N] FILE...
"""

import argparse
import concurrent.futures
import gc
import hashlib
import importlib.resources
import os
import sys
import time
import xml.etree.ElementTree as ET

TC6 = "http://www.plcopen.org/xml/tc6_0201"
XHTML = "http://www.w3.org/1999/xhtml"

# The alternative removed from blark's grammar (see the module's doc).
BARE_LIST = (
    '                    | array_initial_element ( "," array_initial_element )*'
    "         -> bare_array_initialization\n"
)

_parser = None


def parser():
    """blark's grammar and Earley parser, as blark builds them, less the
    bare initialiser list; built once per worker process."""
    global _parser
    if _parser is None:
        import lark
        from blark.parse import BlarkStartingRule

        package = importlib.resources.files("blark")
        grammar = package.joinpath("iec.lark").read_text()
        if grammar.count(BARE_LIST) != 1:
            raise SystemExit(
                "blark's grammar has changed: the bare initialiser list "
                "alternative was not found exactly once"
            )
        _parser = lark.Lark(
            grammar.replace(BARE_LIST, ""),
            parser="earley",
            maybe_placeholders=True,
            propagate_positions=True,
            start=[rule.name for rule in BlarkStartingRule],
            import_paths=[str(package)],
        )
    return _parser


def blark_errors(source, name, rule):
    """blark's parse of `source` from grammar rule `rule`: its error, or None."""
    from blark.parse import parse_source_code

    # The parse makes millions of objects and few cycles: the cyclic
    # garbage collector's passes over them cost a fifth of the time.
    gc.disable()
    try:
        result = parse_source_code(source, fn=name, parser=parser(), starting_rule=rule)
    finally:
        gc.enable()
    return None if result.exception is None else str(result.exception)


def check_st(path):
    """(lines, seconds, errors) of one .st file."""
    start = time.monotonic()
    with open(path, encoding="utf-8") as f:
        source = f.read()
    error = blark_errors(source, path, "iec_source")
    return source.count("\n"), time.monotonic() - start, [error] if error else []


_schema = None


def check_xml(path, xsd):
    """(lines, seconds, errors) of one .xml file: schema errors, then
    blark's errors in each POU's ST body."""
    global _schema
    import xmlschema

    start = time.monotonic()
    if _schema is None:
        _schema = xmlschema.XMLSchema(xsd)
    errors = [f"{e.path}: {e.reason}" for e in _schema.iter_errors(path)]
    root = ET.parse(path).getroot()
    bodies = 0
    for pou in root.iter(f"{{{TC6}}}pou"):
        p = pou.find(f"{{{TC6}}}body/{{{TC6}}}ST/{{{XHTML}}}p")
        if p is None:
            continue
        bodies += 1
        error = blark_errors(p.text or "", f"{path}:{pou.get('name')}", "statement_list")
        if error:
            errors.append(f"POU {pou.get('name')}: {error}")
    if bodies == 0:
        errors.append("no POU with an ST body")
    with open(path, encoding="utf-8") as f:
        lines = sum(1 for _ in f)
    return lines, time.monotonic() - start, errors


def check(path, xsd, max_st_bytes):
    if path.endswith(".st"):
        size = os.path.getsize(path)
        if size > max_st_bytes:
            return None, 0.0, [], f"{size} bytes: above --max-st-bytes, not parsed"
        return (*check_st(path), None)
    if path.endswith(".xml"):
        return (*check_xml(path, xsd), None)
    return None, 0.0, ["neither .st nor .xml"], None


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--xsd", required=True, help="tc6_xml_v201.xsd")
    ap.add_argument("--xsd-sha256", required=True, help="its expected SHA-256")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument(
        "--max-st-bytes",
        type=int,
        default=sys.maxsize,
        help="skip (and list) .st files larger than this",
    )
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    digest = sha256(args.xsd)
    if digest != args.xsd_sha256:
        sys.exit(f"{args.xsd}: SHA-256 {digest}, expected {args.xsd_sha256}")

    # Largest first: the longest parse starts at once.
    files = sorted(args.files, key=os.path.getsize, reverse=True)
    failed = 0
    skipped = []
    start = time.monotonic()
    with concurrent.futures.ProcessPoolExecutor(max_workers=args.jobs) as pool:
        jobs = {pool.submit(check, f, args.xsd, args.max_st_bytes): f for f in files}
        for job in concurrent.futures.as_completed(jobs):
            path = jobs[job]
            lines, seconds, errors, skip = job.result()
            if skip:
                skipped.append(path)
                print(f"SKIP {path}: {skip}", flush=True)
            elif errors:
                failed += 1
                print(f"FAIL {path}: {lines} lines, {seconds:.1f} s", flush=True)
                for e in errors[:5]:
                    print(f"  {e[:800]}", flush=True)
                if len(errors) > 5:
                    print(f"  ... {len(errors) - 5} more", flush=True)
            else:
                print(f"OK   {path}: {lines} lines, {seconds:.1f} s", flush=True)
    total = time.monotonic() - start
    print(
        f"iec_check: {len(files) - failed - len(skipped)} files OK, {failed} failing,"
        f" {len(skipped)} skipped, {total:.0f} s"
    )
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
