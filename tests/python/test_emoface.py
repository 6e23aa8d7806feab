"""pytest suite of the Python module (`import emoface`), run by ctest `python.pytest`."""
import csv
import io
import json
import math
import os
import subprocess

import numpy as np
import pytest

import emoface


def test_names():
    assert emoface.emotion_names() == ["sadness", "happiness", "anger", "fear", "disgust", "surprise"]
    assert len(emoface.muscle_names()) == 19
    assert len(emoface.side_parameter_names()) == 35
    names = emoface.parameter_names()
    assert len(names) == 42 and names[0] == "zygomatic_major_l" and names[-1] == "eye_blink_r"
    assert len(emoface.arkit_names()) == 52


def test_emotions_to_muscles_matches_emo2muscle_cli():
    rng = np.random.default_rng(7)
    esv = rng.uniform(0, 1, size=(50, 6))
    esv[0] = 0.0
    esv[1] = [0, 1, 0, 0, 0, 0]
    fmcv = emoface.emotions_to_muscles(esv)
    assert fmcv.shape == (50, 19) and fmcv.dtype == np.float64
    assert np.all(fmcv[0] == 0.0)  # zero emotion: neutral face
    # an independent path to the same rules: the emo2muscle CLI on the same rows
    exe = os.environ.get("EMOFACE_EMO2MUSCLE")
    if not exe:
        pytest.skip("EMOFACE_EMO2MUSCLE not set")
    header = "id," + ",".join(emoface.emotion_names())
    text = header + "\n" + "\n".join(f"r{i}," + ",".join(repr(float(v)) for v in row) for i, row in enumerate(esv))
    out = subprocess.run([exe, "-", "-o", "-"], input=text.encode(), capture_output=True, check=True).stdout
    rows = [r for r in csv.reader(io.StringIO(out.decode())) if r and not r[0].startswith("#")]
    cols = [rows[0].index(m) for m in emoface.muscle_names()]
    cli = np.array([[float(r[c]) for c in cols] for r in rows[1:]])
    np.testing.assert_allclose(fmcv, cli, rtol=0, atol=5e-7)  # the CLI writes 6 decimals


def test_vectorised_equals_row_by_row_and_sides_and_arkit():
    esv = np.array([[0.2, 0.7, 0, 0, 0, 0.4], [0, 0, 0.9, 0, 0.3, 0]])
    batch = emoface.emotions_to_muscles(esv)
    for i in range(2):
        np.testing.assert_array_equal(batch[i], emoface.emotions_to_muscles(esv[i]))
    sides = emoface.emotions_to_sides(esv)
    assert sides.shape == (2, 35)
    names = emoface.side_parameter_names()
    assert sides[0, names.index("zygomatic_major_l")] == batch[0, 0] == sides[0, names.index("zygomatic_major_r")]
    arkit = emoface.emotions_to_arkit(esv)
    assert arkit.shape == (2, 52) and np.all((arkit >= 0) & (arkit <= 1))
    smile = emoface.arkit_names().index("mouthSmile_L")
    assert arkit[0, smile] > arkit[1, smile]


@pytest.mark.parametrize("bad", [np.zeros((3, 5)), np.zeros((2, 3, 6)), np.full((1, 6), np.nan),
                                 np.full((1, 6), 1.5), np.full((1, 6), -np.inf)])
def test_bad_emotions_raise(bad):
    with pytest.raises(ValueError):
        emoface.emotions_to_muscles(bad)


def test_character_events_update_and_snapshot():
    c = emoface.Character({"format": "emoface.character", "version": "1.0", "seed": 4})
    assert c.push_event({"emotions": {"happiness": 0.9}}) == (True, "")
    ok, msg = c.push_event({"emotions": {"joy": 1}})
    assert not ok and "joy" in msg
    for _ in range(120):
        c.update(1 / 60)
    assert c.emotions[1] == 0.9
    p = c.parameters
    assert p.shape == (42,) and p[0] > 0.3
    assert c.arkit.shape == (52,)
    assert math.isclose(c.input_time - c.output_time, c.latency, abs_tol=1e-9)
    d = emoface.Character.restore(c.snapshot())
    for _ in range(60):
        c.update(1 / 60)
        d.update(1 / 60)
        np.testing.assert_array_equal(c.parameters, d.parameters)
    with pytest.raises(ValueError):
        emoface.Character('{"format": "emoface.character", "version": "1.0", "fps": 1}')
    with pytest.raises(ValueError):
        c.update(float("nan"))


def test_face_deformation_arrays():
    face = emoface.Face()
    neutral = face.neutral
    assert neutral.ndim == 2 and neutral.shape[1] == 3 and face.faces.shape[1] == 3
    zero = np.zeros(42)
    # the default (MakeHuman) head rebuilds its lip-bound vertices from the lip surface: equal to
    # ~5e-10 m, not bit for bit (the generic face is exact)
    np.testing.assert_allclose(face.deform(zero), neutral, rtol=0, atol=1e-8)
    params = np.zeros((3, 42))
    params[1, 0] = params[1, 1] = 1.0  # zygomatic major, both sides
    params[2, emoface.parameter_names().index("masseter")] = 0.8
    batch = face.deform(params)
    assert batch.shape == (3,) + neutral.shape
    np.testing.assert_array_equal(batch[1], face.deform(params[1]))
    assert np.abs(batch[1] - neutral).max() > 1e-3
    with pytest.raises(ValueError):
        face.deform(np.zeros(41))


def test_character_with_face_returns_vertices():
    c = emoface.Character({"format": "emoface.character", "version": "1.0", "face": "default"})
    c.update(0.5)
    v = c.vertices()
    assert v.shape[1] == 3 and c.faces().shape[1] == 3


def _mindmotion_graph():
    graph = os.environ.get("EMOFACE_TEST_GRAPH")
    if not graph or not os.path.exists(graph):
        pytest.skip("EMOFACE_TEST_GRAPH not set (ctest fixture capi.make_graph)")
    return graph


REX = os.path.join(os.path.dirname(__file__), "..", "..", "data", "mindmap", "crowd", "rex.json")
QUIET = {"format": "emoface.character", "version": "1.1", "seed": 3,
         "blinks": False, "gaze_noise": False, "head_noise": False}


def test_mindmotion_character_moves_by_synthesized_motion():
    graph = _mindmotion_graph()
    a = emoface.Character.mindmotion(graph, REX, QUIET)
    b = emoface.Character.mindmotion(graph, REX, json.dumps(QUIET))
    a.update(1.0)
    b.update(1.0)
    rest = a.parameters
    assert a.push_stimulus("insult") == (True, "")
    assert b.push_event({"stimulus": "insult"}) == (True, "")
    for _ in range(120):
        a.update(1 / 60)
        b.update(1 / 60)
        assert np.array_equal(a.parameters, b.parameters)  # same seed, same stream
    assert np.max(np.abs(a.parameters - rest)) > 0.05
    assert a.emotions[2] > 0.1  # rex is angry
    assert a.arkit.shape == (52,) and np.all((a.arkit >= 0) & (a.arkit <= 1))
    assert a.facs.shape == (len(a.facs),) and len(a.facs) > 0
    applied, message = a.push_stimulus("tickle")
    assert not applied and "tickle" in message
    assert not a.push_stimulus("tickle", {"happiness": 2.0})[0]  # out of [0, 1]
    assert a.push_stimulus("tickle", {"happiness": 1.0}) == (True, "")
    assert not a.push_event({"emotions": {"happiness": 1}})[0]
    with pytest.raises(ValueError):
        a.snapshot()  # not available for this source yet


def test_mindmotion_bad_files_and_config_raise():
    graph = _mindmotion_graph()
    with pytest.raises(OSError):
        emoface.Character.mindmotion("/no/such/graph.json", REX)
    with pytest.raises(ValueError):
        emoface.Character.mindmotion(REX, REX)  # a mind map is no motion graph
    with pytest.raises(ValueError):
        emoface.Character.mindmotion(graph, REX, {"format": "emoface.character", "version": "1.1",
                                                  "source": {"kind": "direct"}, "colour": 1})
    with pytest.raises(ValueError):
        emoface.Character.mindmotion(graph, REX, {"format": "emoface.character", "version": "1.1",
                                                  "source": {"kind": "parlee", "domain": "x"}})
