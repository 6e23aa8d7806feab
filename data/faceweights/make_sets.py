#!/usr/bin/env python3
"""Writes data/faceweights/arkit.json and facs.json (the emoface.faceweights 1.0 weight sets).

The sets are hand-made data; this script only keeps the shared source list and the left/right
expansion in one place. Run from the repository root:  python3 data/faceweights/make_sets.py
Each row: target name, terms {input: weight}, FACS AU(s), source ids, note. An input is a face
parameter name (a level in [0, 1]) or, for the signed angle parameters, "<name>+" / "<name>-": the
positive / negative half of the angle divided by the set's range for it (clamped to [0, 1]).
"""
import json
import os

GENERATOR = "emoface 0.1.0"
SOURCES = [
    {"id": "thesis-A", "citation": "Bui (2004), Creating emotions and facial expressions for embodied "
     "agents, Appendix A, Tables A.1-A.2: FACS action units and the muscles producing them"},
    {"id": "thesis-B", "citation": "Bui (2004), Appendix B: the 19 implemented muscles and what each "
     "moves (after Parke and Waters 1996)"},
    {"id": "facs", "citation": "Ekman, Friesen and Hager (2002), Facial Action Coding System: the "
     "manual, action unit definitions (AU numbers, names, muscular basis)"},
    {"id": "apple", "citation": "Apple, ARKit documentation, ARFaceAnchor.BlendShapeLocation: the 52 "
     "coefficients and the motion each describes (raw values such as eyeBlink_L)"},
    {"id": "ozel", "citation": "M. Ozel, ARKit to FACS Cheat Sheet, melindaozel.com/arkit-to-facs-"
     "cheat-sheet (published ARKit shape <-> AU correspondences)"},
    {"id": "emoface", "citation": "emoface docs/muscles.md: gaze limits of the muscle model (yaw 0.55 "
     "rad, pitch 0.38 rad) and head pose conventions"},
]
SIDES = [("L", "l"), ("R", "r")]


def sided(name, terms, facs, sources, note=""):
    rows = []
    for S, s in SIDES:
        rows.append(row(name.replace("{S}", S), {k.replace("{s}", s): v for k, v in terms.items()},
                        facs, sources, note))
    return rows


def row(name, terms, facs, sources, note=""):
    r = {"name": name, "terms": terms, "facs": facs, "sources": sources}
    if note:
        r["note"] = note
    return r


def arkit():
    t = []
    t += sided("browDown_{S}", {"corrugator_supercilii_{s}": 0.45, "depressor_supercilii_{s}": 0.35,
                                "depressor_glabellae_{s}": 0.2}, "AU4",
               ["thesis-A", "thesis-B", "facs", "apple", "ozel"],
               "AU4 brow lowerer: corrugator + depressor supercilii (thesis Table A.1) and procerus "
               "(our depressor_glabellae, FACS manual); the three cannot be told apart from this shape "
               "alone, so from_arkit shares it between them")
    t.append(row("browInnerUp", {"frontalis_medialis_l": 0.5, "frontalis_medialis_r": 0.5}, "AU1",
                 ["thesis-A", "facs", "apple", "ozel"], "both inner brows: the mean of the two sides"))
    t += sided("browOuterUp_{S}", {"frontalis_lateralis_{s}": 1.0}, "AU2",
               ["thesis-A", "facs", "apple", "ozel"])
    t.append(row("cheekPuff", {}, "AU34",
                 ["facs", "apple", "ozel"], "no muscle: puffing the cheeks with air (buccinator with "
                 "closed lips) is not part of the thesis muscle set"))
    t += sided("cheekSquint_{S}", {"orbicularis_oculi_orbitalis_{s}": 1.0}, "AU6",
               ["thesis-A", "thesis-B", "facs", "apple", "ozel"])
    t += sided("eyeBlink_{S}", {"eye_blink_{s}": 1.0}, "AU45/AU43",
               ["thesis-A", "facs", "apple", "ozel"],
               "lid closure: emoface's eye_blink_* parameters (AU45), not the palpebralis muscle")
    t += sided("eyeLookDown_{S}", {"eye_gaze_pitch-": 1.0}, "AU64",
               ["thesis-A", "apple", "emoface"], "both eyes share one gaze; full weight = the pitch "
               "limit of the muscle model")
    t.append(row("eyeLookIn_L", {"eye_gaze_yaw-": 1.0}, "AU62", ["thesis-A", "apple", "emoface"],
                 "the left eye turns towards the nose = gaze to the subject's right (yaw < 0)"))
    t.append(row("eyeLookIn_R", {"eye_gaze_yaw+": 1.0}, "AU61", ["thesis-A", "apple", "emoface"],
                 "the right eye turns towards the nose = gaze to the subject's left (yaw > 0)"))
    t.append(row("eyeLookOut_L", {"eye_gaze_yaw+": 1.0}, "AU61", ["thesis-A", "apple", "emoface"],
                 "the left eye turns outwards = gaze to the subject's left"))
    t.append(row("eyeLookOut_R", {"eye_gaze_yaw-": 1.0}, "AU62", ["thesis-A", "apple", "emoface"],
                 "the right eye turns outwards = gaze to the subject's right"))
    t += sided("eyeLookUp_{S}", {"eye_gaze_pitch+": 1.0}, "AU63", ["thesis-A", "apple", "emoface"])
    t += sided("eyeSquint_{S}", {"orbicularis_oculi_palpebralis_{s}": 1.0}, "AU7",
               ["thesis-A", "facs", "apple", "ozel"],
               "AU7 lid tightener: orbicularis oculi pars palpebralis narrows the eye and raises the "
               "lower lid")
    t += sided("eyeWide_{S}", {"levator_palpebrae_superioris_{s}": 1.0}, "AU5",
               ["thesis-A", "facs", "apple", "ozel"])
    t.append(row("jawForward", {}, "AU29", ["facs", "apple"],
                 "no muscle: the muscle model rotates the jaw but does not thrust it forward"))
    t.append(row("jawLeft", {}, "AU30", ["facs", "apple"], "no muscle: no sideways jaw motion"))
    t.append(row("jawOpen", {"masseter": 1.0}, "AU26/AU27",
                 ["thesis-A", "thesis-B", "facs", "apple", "ozel"],
                 "the masseter parameter drives the jaw rotation (thesis 2.4.4)"))
    t.append(row("jawRight", {}, "AU30", ["facs", "apple"], "no muscle: no sideways jaw motion"))
    t.append(row("mouthClose", {}, "AU26+AU24", ["apple", "ozel"],
                 "no single muscle: lips held together while the jaw is open (a combination, not a "
                 "shape of its own in the muscle model)"))
    t += sided("mouthDimple_{S}", {"risorius_{s}": 0.5}, "AU14",
               ["thesis-B", "facs", "apple", "ozel"],
               "AU14 is the buccinator (not modelled); thesis Appendix B: the risorius dimples the "
               "cheek, so half of it")
    t += sided("mouthFrown_{S}", {"triangularis_{s}": 1.0}, "AU15",
               ["thesis-A", "facs", "apple", "ozel"])
    t.append(row("mouthFunnel", {"orbicularis_oris_funneler": 1.0}, "AU22",
                 ["thesis-A", "thesis-B", "facs", "apple", "ozel"]))
    t.append(row("mouthLeft", {}, "", ["apple"], "no muscle: sideways shift of the whole mouth"))
    t += sided("mouthLowerDown_{S}", {"depressor_labii_{s}": 1.0}, "AU16",
               ["thesis-A", "facs", "apple", "ozel"])
    t += sided("mouthPress_{S}", {"orbicularis_oris_pressor": 1.0}, "AU24",
               ["thesis-A", "thesis-B", "facs", "apple", "ozel"],
               "the pressor is one parameter for both sides")
    t.append(row("mouthPucker", {"orbicularis_oris_funneler": 0.6}, "AU18",
                 ["thesis-A", "thesis-B", "facs", "apple", "ozel"],
                 "AU18 is the incisivii (not modelled); the thesis funneler includes the pucker "
                 "e(p), so part of it"))
    t.append(row("mouthRight", {}, "", ["apple"], "no muscle: sideways shift of the whole mouth"))
    t.append(row("mouthRollLower", {"orbicularis_oris_pressor": 0.3}, "AU28",
                 ["thesis-B", "facs", "apple", "ozel"],
                 "thesis Appendix B: the pressor can roll the lips in over the teeth"))
    t.append(row("mouthRollUpper", {"orbicularis_oris_pressor": 0.3}, "AU28",
                 ["thesis-B", "facs", "apple", "ozel"],
                 "thesis Appendix B: the pressor can roll the lips in over the teeth"))
    t.append(row("mouthShrugLower", {"mentalis_l": 0.5, "mentalis_r": 0.5}, "AU17",
                 ["thesis-A", "thesis-B", "facs", "apple", "ozel"]))
    t.append(row("mouthShrugUpper", {"mentalis_l": 0.25, "mentalis_r": 0.25}, "AU17",
                 ["thesis-B", "apple", "ozel"],
                 "the chin raiser presses the lower lip up against the upper lip"))
    t += sided("mouthSmile_{S}", {"zygomatic_major_{s}": 1.0, "zygomatic_minor_{s}": 0.3}, "AU12",
               ["thesis-A", "thesis-B", "facs", "apple", "ozel"],
               "thesis Appendix B: the zygomatic minor also pulls the mouth corners up and out")
    t += sided("mouthStretch_{S}", {"risorius_{s}": 1.0}, "AU20",
               ["thesis-A", "facs", "apple", "ozel"])
    t += sided("mouthUpperUp_{S}", {"levator_labii_superioris_{s}": 1.0,
                                    "zygomatic_minor_{s}": 0.5, "levator_labii_nasi_{s}": 0.3},
               "AU10", ["thesis-A", "thesis-B", "facs", "apple", "ozel"],
               "AU10; the zygomatic minor (AU11) and the nasal levator (AU9, thesis Appendix B: 'may "
               "raise the outer part of the upper lip') raise it too")
    t += sided("noseSneer_{S}", {"levator_labii_nasi_{s}": 1.0, "depressor_glabellae_{s}": 0.3},
               "AU9", ["thesis-A", "thesis-B", "facs", "apple", "ozel"],
               "AU9; the procerus (depressor_glabellae) wrinkles the nose root")
    t.append(row("tongueOut", {}, "AU19", ["facs", "apple"],
                 "no muscle: the tongue is not animated by the muscle model"))
    return {"set": "arkit", "naming": "arkit",
            "description": "The 52 ARKit blend shapes (ARFaceAnchor.BlendShapeLocation raw values, "
            "e.g. eyeBlink_L; _L/_R = the subject's own left/right) as linear functions of the emoface "
            "face parameters, clamped to [0, 1].",
            "ranges": {"eye_gaze_yaw": 0.55, "eye_gaze_pitch": 0.38}, "targets": t}


def facs():
    t = []
    t += sided("AU1_{S}", {"frontalis_medialis_{s}": 1.0}, "AU1", ["thesis-A", "facs"],
               "inner brow raiser")
    t += sided("AU2_{S}", {"frontalis_lateralis_{s}": 1.0}, "AU2", ["thesis-A", "facs"],
               "outer brow raiser")
    t += sided("AU4_{S}", {"corrugator_supercilii_{s}": 0.45, "depressor_supercilii_{s}": 0.35,
                           "depressor_glabellae_{s}": 0.2}, "AU4", ["thesis-A", "facs"],
               "brow lowerer: corrugator and depressor supercilii (thesis Table A.1), procerus "
               "(depressor_glabellae, FACS manual)")
    t += sided("AU5_{S}", {"levator_palpebrae_superioris_{s}": 1.0}, "AU5", ["thesis-A", "facs"],
               "upper lid raiser")
    t += sided("AU6_{S}", {"orbicularis_oculi_orbitalis_{s}": 1.0}, "AU6", ["thesis-A", "facs"],
               "cheek raiser")
    t += sided("AU7_{S}", {"orbicularis_oculi_palpebralis_{s}": 1.0}, "AU7", ["thesis-A", "facs"],
               "lid tightener")
    t += sided("AU9_{S}", {"levator_labii_nasi_{s}": 1.0, "depressor_glabellae_{s}": 0.3}, "AU9",
               ["thesis-A", "thesis-B", "facs"], "nose wrinkler (+ procerus at the nose root)")
    t += sided("AU10_{S}", {"levator_labii_superioris_{s}": 1.0}, "AU10", ["thesis-A", "facs"],
               "upper lip raiser")
    t += sided("AU11_{S}", {"zygomatic_minor_{s}": 1.0}, "AU11", ["facs", "thesis-B"],
               "nasolabial deepener = zygomaticus minor in the FACS manual; thesis Table A.1 swaps "
               "the muscles of AU11 (levator anguli oris) and AU13 (zygomaticus minor)")
    t += sided("AU12_{S}", {"zygomatic_major_{s}": 1.0}, "AU12", ["thesis-A", "facs"],
               "lip corner puller")
    t.append(row("AU13", {}, "AU13", ["facs", "thesis-A"],
                 "no muscle: sharp lip puller (levator anguli oris) is not in the thesis muscle set"))
    t += sided("AU14_{S}", {"risorius_{s}": 0.5}, "AU14", ["thesis-B", "facs"],
               "dimpler: the buccinator is not modelled; thesis Appendix B: the risorius dimples "
               "the cheek, so half of it")
    t += sided("AU15_{S}", {"triangularis_{s}": 1.0}, "AU15", ["thesis-A", "facs"],
               "lip corner depressor")
    t += sided("AU16_{S}", {"depressor_labii_{s}": 1.0}, "AU16", ["thesis-A", "facs"],
               "lower lip depressor")
    t += sided("AU17_{S}", {"mentalis_{s}": 1.0}, "AU17", ["thesis-A", "facs"], "chin raiser")
    t.append(row("AU18", {"orbicularis_oris_funneler": 0.6}, "AU18",
                 ["thesis-A", "thesis-B", "facs"],
                 "lip pucker: the incisivii are not modelled; the funneler includes the pucker"))
    t += sided("AU20_{S}", {"risorius_{s}": 1.0}, "AU20", ["thesis-A", "facs"], "lip stretcher")
    t.append(row("AU22", {"orbicularis_oris_funneler": 1.0}, "AU22", ["thesis-A", "facs"],
                 "lip funneler"))
    t.append(row("AU23", {"orbicularis_oris_pressor": 0.5}, "AU23",
                 ["thesis-A", "thesis-B", "facs"],
                 "lip tightener: orbicularis oris; the pressor tightens the red of the lips"))
    t.append(row("AU24", {"orbicularis_oris_pressor": 1.0}, "AU24", ["thesis-A", "facs"],
                 "lip pressor"))
    t.append(row("AU25", {"depressor_labii_l": 0.5, "depressor_labii_r": 0.5}, "AU25",
                 ["thesis-A", "facs"], "lips part: depressor labii inferioris (thesis Table A.2)"))
    t.append(row("AU26", {"masseter": 1.0}, "AU26", ["thesis-A", "facs"],
                 "jaw drop: the masseter parameter rotates the jaw"))
    t.append(row("AU27", {}, "AU27", ["thesis-A", "facs"],
                 "no muscle: mouth stretch (pterygoids, digastric) beyond the jaw rotation of AU26"))
    t.append(row("AU28", {"orbicularis_oris_pressor": 0.3}, "AU28", ["thesis-A", "thesis-B", "facs"],
                 "lip suck: the pressor rolls the lips in"))
    t += sided("AU45_{S}", {"eye_blink_{s}": 1.0}, "AU45", ["thesis-A", "facs"],
               "blink (and AU43 eyes closed when held): emoface's eye_blink_* parameters; a one-sided "
               "AU45 is AU46 (wink)")
    t.append(row("AU51", {"head_yaw+": 1.0}, "AU51", ["thesis-A", "facs", "emoface"],
                 "head turn left; full intensity at the set's head_yaw range"))
    t.append(row("AU52", {"head_yaw-": 1.0}, "AU52", ["thesis-A", "facs", "emoface"],
                 "head turn right"))
    t.append(row("AU53", {"head_pitch+": 1.0}, "AU53", ["thesis-A", "facs", "emoface"], "head up"))
    t.append(row("AU54", {"head_pitch-": 1.0}, "AU54", ["thesis-A", "facs", "emoface"],
                 "head down"))
    t.append(row("AU55", {"head_roll-": 1.0}, "AU55", ["thesis-A", "facs", "emoface"],
                 "head tilt left (top of the head towards the subject's left = negative roll)"))
    t.append(row("AU56", {"head_roll+": 1.0}, "AU56", ["thesis-A", "facs", "emoface"],
                 "head tilt right"))
    t.append(row("AU61", {"eye_gaze_yaw+": 1.0}, "AU61", ["thesis-A", "facs", "emoface"],
                 "eyes turn left"))
    t.append(row("AU62", {"eye_gaze_yaw-": 1.0}, "AU62", ["thesis-A", "facs", "emoface"],
                 "eyes turn right"))
    t.append(row("AU63", {"eye_gaze_pitch+": 1.0}, "AU63", ["thesis-A", "facs", "emoface"],
                 "eyes up"))
    t.append(row("AU64", {"eye_gaze_pitch-": 1.0}, "AU64", ["thesis-A", "facs", "emoface"],
                 "eyes down"))
    return {"set": "facs", "naming": "facs",
            "description": "FACS action units as linear functions of the emoface face parameters, "
            "clamped to [0, 1] (1 = maximum intensity E). Paired muscles give one row per side "
            "(AU12_L, AU12_R = the subject's left/right).",
            "ranges": {"eye_gaze_yaw": 0.55, "eye_gaze_pitch": 0.38, "head_yaw": 0.7854,
                       "head_pitch": 0.5236, "head_roll": 0.5236},
            "targets": t}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    for body in (arkit(), facs()):
        doc = {"format": "emoface.faceweights", "version": "1.0", "generator": GENERATOR}
        doc.update({"set": body["set"], "naming": body["naming"], "description": body["description"],
                    "ranges": body["ranges"], "sources": SOURCES, "targets": body["targets"]})
        with open(os.path.join(here, body["set"] + ".json"), "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
