#!/usr/bin/env python3
"""Opens every file that the test `cargo test -p fair-cad --test cad occ_check` wrote (into
`target/tmp/cad-check`, or DIR = `$FAIR_CAD_CHECK_DIR`) with
OpenCASCADE's readers (IGESControl_Reader, STEPControl_Reader) and ezdxf, evaluates each
curve or surface at the parameters in DIR/check.json (1 000 per curve, 32 x 32 per surface),
and compares with our own evaluation to 1e-9 of the shape's size; the faired points must lie
on the curve read back at their parameters to 1e-9 of the size too (plus the rebuild's stated
deviation for a rebuilt curve). Prints one line per file and a closing line
'N passed, N failed'; exits 1 on any failure.

    python tests/python/check_cad.py DIR

Needs cadquery-ocp-novtk (OpenCASCADE) and ezdxf (see .ci/run).
"""
import json
import sys
from pathlib import Path

import ezdxf
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader
from OCP.Message import Message, Message_Gravity
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

RELATIVE = 1e-9
# OpenCASCADE's readers convert lengths to millimetres (its session unit): the file's unit,
# read from the header, is checked by comparing with our coordinates times this factor.
MILLIMETRES = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "um": 1e-3, "in": 25.4, "ft": 304.8}


def quiet_occ():
    """OpenCASCADE's readers print transfer statistics; keep only failures."""
    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


def occ_shape(path, reader_class):
    reader = reader_class()
    if reader.ReadFile(str(path)) != IFSelect_RetDone:
        raise RuntimeError(f"{path}: OpenCASCADE could not read the file")
    if reader.TransferRoots() == 0:
        raise RuntimeError(f"{path}: OpenCASCADE transferred nothing")
    return reader.OneShape()


def explore(shape, kind, cast):
    found = []
    explorer = TopExp_Explorer(shape, kind)
    while explorer.More():
        found.append(cast(explorer.Current()))
        explorer.Next()
    return found


def occ_curve(path, reader_class):
    """The one edge's evaluator and its parameter range."""
    edges = explore(occ_shape(path, reader_class), TopAbs_EDGE, TopoDS.Edge)
    if len(edges) != 1:
        raise RuntimeError(f"{path}: {len(edges)} edges, expected 1")
    adaptor = BRepAdaptor_Curve(edges[0])

    def evaluate(t):
        p = adaptor.Value(t)
        return (p.X(), p.Y(), p.Z())

    return evaluate, (adaptor.FirstParameter(), adaptor.LastParameter())


def occ_surface(path, reader_class):
    faces = explore(occ_shape(path, reader_class), TopAbs_FACE, TopoDS.Face)
    if len(faces) != 1:
        raise RuntimeError(f"{path}: {len(faces)} faces, expected 1")
    adaptor = BRepAdaptor_Surface(faces[0], False)

    def evaluate(uv):
        p = adaptor.Value(uv[0], uv[1])
        return (p.X(), p.Y(), p.Z())

    domain = ((adaptor.FirstUParameter(), adaptor.LastUParameter()),
              (adaptor.FirstVParameter(), adaptor.LastVParameter()))
    return evaluate, domain


def ezdxf_curve(path):
    doc = ezdxf.readfile(str(path))
    auditor = doc.audit()
    if auditor.has_errors:
        raise RuntimeError(f"{path}: ezdxf audit found errors: {auditor.errors}")
    splines = doc.modelspace().query("SPLINE")
    if len(splines) != 1:
        raise RuntimeError(f"{path}: {len(splines)} SPLINE entities, expected 1")
    spline = splines[0].construction_tool()
    knots = list(splines[0].knots)
    first, last = knots[0], knots[-1]

    def evaluate(t):
        # ezdxf's BSpline rescales a knot vector that does not start at 0 onto [0, 1].
        s = (t - first) / (last - first) if first != 0.0 else t
        p = spline.point(s)
        return (p.x, p.y, p.z)

    return evaluate, (first, last)


def distance(a, b):
    return sum((x - y) ** 2 for x, y in zip(a, b)) ** 0.5


def check(record, directory, fmt):
    path = directory / record["files"][fmt]
    scale = 1.0 if fmt == "dxf" else MILLIMETRES[record["units"]]
    size = record["size"] * scale
    if record["kind"] == "curve":
        if fmt == "dxf":
            evaluate, domain = ezdxf_curve(path)
        else:
            evaluate, domain = occ_curve(path, IGESControl_Reader if fmt == "iges" else STEPControl_Reader)
        expected_domain = record["domain"]
        if max(abs(a - b) for a, b in zip(domain, expected_domain)) > RELATIVE * max(1.0, abs(expected_domain[1])):
            raise RuntimeError(f"{path}: parameter range {domain}, expected {expected_domain}")
    else:
        evaluate, domain = occ_surface(path, IGESControl_Reader if fmt == "iges" else STEPControl_Reader)
    scaled = lambda p: [scale * c for c in p]  # noqa: E731
    worst = max(distance(evaluate(t), scaled(p)) for t, p in zip(record["params"], record["points"]))
    if worst > RELATIVE * size:
        raise RuntimeError(f"{path}: evaluation differs by {worst:.3e} (size {size:.3e})")
    on_curve = max((distance(evaluate(t), scaled(p))
                    for t, p in zip(record["data_params"], record["data_points"])), default=0.0)
    if on_curve > RELATIVE * size + scale * record["data_slack"]:
        raise RuntimeError(f"{path}: a faired point lies {on_curve:.3e} from the curve")
    return worst / size, on_curve / size


def main(directory):
    directory = Path(directory)
    quiet_occ()
    records = json.loads((directory / "check.json").read_text())
    passed = failed = 0
    for record in records:
        for fmt in record["files"]:
            try:
                evaluation, points = check(record, directory, fmt)
                print(f"ok   {record['files'][fmt]:28} evaluation {evaluation:.1e}, "
                      f"faired points {points:.1e} (relative to size)")
                passed += 1
            except Exception as error:  # one line per failure, then go on
                print(f"FAIL {record['files'][fmt]:28} {error}")
                failed += 1
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "target/tmp/cad-check"))
