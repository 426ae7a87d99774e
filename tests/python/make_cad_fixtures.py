#!/usr/bin/env python3
"""Writes the OpenCASCADE and ezdxf fixtures of data/reference/cad/ (run once, by hand).

Each file holds one shape that OpenCASCADE (cadquery-ocp-novtk) or ezdxf wrote itself, so that
the readers of `crates/cad` are tested on files that a CAD system produced, not only on ours.
`fixtures.json` records the exact geometry given to the writers (knots with multiplicities
expanded, poles, weights), so that a test can compare what our reader finds with what was
written (to the digits the writer prints).

    python tests/python/make_cad_fixtures.py data/reference/cad
"""
import json
import math
import sys
from pathlib import Path

import ezdxf
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Controller, IGESControl_Writer
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int, Array2_double, Array2_gp_Pnt
from OCP.gp import gp_Pnt


def array1(values, kind):
    arr = kind(1, len(values))
    for i, v in enumerate(values):
        arr.SetValue(i + 1, v)
    return arr


def flat_knots(knots, mults):
    return [k for k, m in zip(knots, mults) for _ in range(m)]


def curve(poles, knots, mults, degree, weights=None):
    p = array1([gp_Pnt(*q) for q in poles], Array1_gp_Pnt)
    k = array1(knots, Array1_double)
    m = array1(mults, Array1_int)
    if weights is None:
        return Geom_BSplineCurve(p, k, m, degree)
    return Geom_BSplineCurve(p, array1(weights, Array1_double), k, m, degree)


def surface(net, uk, um, vk, vm, p, q, weights=None):
    rows, cols = len(net), len(net[0])
    poles = Array2_gp_Pnt(1, rows, 1, cols)
    for i in range(rows):
        for j in range(cols):
            poles.SetValue(i + 1, j + 1, gp_Pnt(*net[i][j]))
    args = [poles]
    if weights is not None:
        w = Array2_double(1, rows, 1, cols)
        for i in range(rows):
            for j in range(cols):
                w.SetValue(i + 1, j + 1, weights[i][j])
        args.append(w)
    args += [array1(uk, Array1_double), array1(vk, Array1_double),
             array1(um, Array1_int), array1(vm, Array1_int), p, q]
    return Geom_BSplineSurface(*args)


def main(out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    record = {"provenance": "written by tests/python/make_cad_fixtures.py with OpenCASCADE "
                            "(cadquery-ocp-novtk 8.0.1.1.0) and ezdxf " + ezdxf.__version__,
              "curves": {}, "surfaces": {}}

    # A cubic 3D curve with a double interior knot, non-uniform knots.
    c3 = dict(poles=[(0, 0, 0), (1.25, 2, 0.5), (3, 2.5, -0.25), (4.5, 1, 1), (6, -0.5, 0.75),
                     (7.2, 0.3, 0.1), (9, 1.1, 0)],
              knots=[0.0, 0.7, 1.9, 3.0], mults=[4, 1, 2, 4], degree=3, weights=None)
    # A rational quadratic: a quarter circle of radius 2 centred at (1, 1, 0) plus a second quarter.
    s = math.sqrt(0.5)
    arc = dict(poles=[(3, 1, 0), (3, 3, 0), (1, 3, 0), (-1, 3, 0), (-1, 1, 0)],
               knots=[0.0, 0.5, 1.0], mults=[3, 2, 3], degree=2, weights=[1, s, 1, s, 1])
    shapes = {"occ_curve3d": c3, "occ_rational_arc": arc}
    edges = {}
    for name, c in shapes.items():
        g = curve(c["poles"], c["knots"], c["mults"], c["degree"], c["weights"])
        edges[name] = BRepBuilderAPI_MakeEdge(g).Edge()
        record["curves"][name] = {
            "degree": c["degree"], "knots": flat_knots(c["knots"], c["mults"]),
            "control_points": [list(map(float, q)) for q in c["poles"]],
            "weights": [float(w) for w in (c["weights"] or [1.0] * len(c["poles"]))]}

    # An edge on a part of the 3D curve: STEP writes a TRIMMED_CURVE with parameter trims.
    g = curve(c3["poles"], c3["knots"], c3["mults"], c3["degree"])
    trimmed = BRepBuilderAPI_MakeEdge(g, 0.5, 2.5).Edge()
    record["trimmed"] = {"occ_trimmed": {"basis": "occ_curve3d", "range": [0.5, 2.5]}}

    # A bicubic surface, 5 x 4 poles, a rational bump in one weight.
    net = [[(i * 1.5, j * 1.25, 0.3 * math.sin(i + 2 * j)) for j in range(4)] for i in range(5)]
    wts = [[1.0] * 4 for _ in range(5)]
    wts[2][1] = 1.5
    sf = dict(net=net, uk=[0.0, 0.4, 1.0], um=[4, 1, 4], vk=[0.0, 2.0], vm=[4, 4], p=3, q=3)
    faces = {}
    for name, w in (("occ_surface", None), ("occ_rational_surface", wts)):
        g = surface(sf["net"], sf["uk"], sf["um"], sf["vk"], sf["vm"], sf["p"], sf["q"], w)
        faces[name] = BRepBuilderAPI_MakeFace(g, 1e-7).Face()
        record["surfaces"][name] = {
            "degree_u": 3, "degree_v": 3,
            "knots_u": flat_knots(sf["uk"], sf["um"]), "knots_v": flat_knots(sf["vk"], sf["vm"]),
            "control_points": [[list(map(float, q)) for q in row] for row in net],
            "weights": w or [[1.0] * 4 for _ in range(5)]}

    IGESControl_Controller.Init_s()
    for name, shape in list(edges.items()) + list(faces.items()):
        Interface_Static.SetCVal_s("write.iges.unit", "MM")
        writer = IGESControl_Writer("MM", 0)
        writer.AddShape(shape)
        writer.ComputeModel()
        assert writer.Write(str(out / f"{name}.igs"))
        step = STEPControl_Writer()
        Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
        Interface_Static.SetCVal_s("write.step.unit", "MM")
        assert step.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone
        assert step.Write(str(out / f"{name}.step")) == IFSelect_RetDone

    step = STEPControl_Writer()
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    assert step.Transfer(trimmed, STEPControl_AsIs) == IFSelect_RetDone
    assert step.Write(str(out / "occ_trimmed.step")) == IFSelect_RetDone

    # ezdxf: a rational 3D spline (the arc above, lifted) in an R2000 drawing, in metres.
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 6
    msp = doc.modelspace()
    msp.add_rational_spline(control_points=arc["poles"], weights=arc["weights"], degree=2,
                            knots=flat_knots(arc["knots"], arc["mults"]))
    msp.add_open_spline(control_points=c3["poles"], degree=3,
                        knots=flat_knots(c3["knots"], c3["mults"]))
    doc.saveas(out / "ezdxf_splines.dxf")
    record["dxf"] = {"ezdxf_splines": ["occ_rational_arc", "occ_curve3d"]}
    (out / "fixtures.json").write_text(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "data/reference/cad")
