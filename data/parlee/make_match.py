#!/usr/bin/env python3
"""Writes match.ndjson: the 90-minute match of thesis §7.4 as events of the football domain.

Usage (from the repository root):  python3 data/parlee/make_match.py > data/parlee/match.ndjson

The story: the against team (oteam) scores at 12', the for team (team) equalises at 30', a long
free-kick from the for team's half at 40' ends, still under their control, in the against team's
penalty area and they score (40.5'), the against team equalises at 80'. Every other minute is open
play. A small state machine mirrors the domain so that every event is applicable; `parlee run`
checks it again against the real domain.
"""
import json
import sys

OTHER = {"team": "oteam", "oteam": "team"}


class Match:
    def __init__(self):
        self.control, self.zone, self.piece = "team", ("hf", "team"), "kickoff"
        self.events = []

    def rel(self, side):
        """Zone relative to `side`: pr, hf, ohf, opr."""
        kind, owner = self.zone
        if owner == side:
            return kind
        return "o" + kind

    def ev(self, t, action, side, outcome, note=""):
        c, o = self.control, OTHER[self.control]
        z = self.rel(side)
        if self.piece == "kickoff":
            assert action == "re-kickoff" and side == c, (t, action)
            self.piece = None
        elif self.piece and self.piece[0] == "freekick":
            kicker = self.piece[1]
            assert action.startswith("take-freekick") and side == kicker or action.startswith("defend-freekick"), (t, action)
            if outcome != "nothing":
                self.piece = None
            if action.startswith("take-freekick"):
                zk = self.rel(kicker)
                if outcome == "advanced":
                    self.zone = ("hf", OTHER[kicker]) if zk == "hf" else ("pr", OTHER[kicker])
                elif outcome == "long":
                    self.zone = ("pr", OTHER[kicker])
                elif outcome == "cleared":
                    self.zone = ("hf", kicker)
                elif outcome == "lost":
                    self.control = OTHER[kicker]
            elif outcome == "won":
                self.control = side
        elif action in ("shot", "long-shot"):
            assert side == c and z == ("opr" if action == "shot" else "ohf"), (t, action, z)
            if outcome == "goal":
                self.control, self.piece, self.zone = o, "kickoff", ("hf", o)
            elif outcome == "penalty":
                self.piece = ("penalty", c)
            elif outcome == "wide":
                self.control, self.zone = o, ("pr", o)
            else:
                self.control = o
        elif action.startswith("pass-from") or action == "kick-away-from-pr":
            assert side == c and action.endswith("-" + z), (t, action, z)
            nxt = {"pr": ("hf", c), "hf": ("hf", o), "ohf": ("pr", o)}
            if outcome == "advanced":
                self.zone = nxt[z]
            elif outcome == "lost":
                self.control = o
            elif outcome == "cleared":
                self.zone, self.control = ("hf", o), o
        elif action.startswith("tackle-in") or action.startswith("block-in"):
            assert side == o and action.endswith("-" + z), (t, action, z)
            if outcome == "won":
                self.control = side
            elif outcome == "foul":
                self.piece = ("freekick", c) if z in ("hf", "ohf") else ("penalty", c)
        else:
            raise AssertionError((t, action))
        e = {"time": t, "action": f"({action} {side})", "outcome": outcome}
        if note:
            e["note"] = note
        self.events.append(e)

    def keep(self, t):
        """A quiet minute: the side on the ball keeps it where it is."""
        c = self.control
        self.ev(t, "pass-from-" + self.rel(c), c, "kept")


def main():
    m = Match()
    m.ev(1, "re-kickoff", "team", "started", "kick-off")
    m.keep(2); m.keep(3)
    m.ev(4, "pass-from-hf", "team", "advanced")
    m.ev(5, "tackle-in-hf", "oteam", "won")
    m.keep(6)
    m.ev(7, "pass-from-hf", "oteam", "advanced")
    m.keep(8)
    m.ev(9, "block-in-hf", "team", "nothing")
    m.ev(10, "pass-from-ohf", "oteam", "advanced")
    m.ev(11, "block-in-pr", "team", "nothing")
    m.ev(12, "shot", "oteam", "goal", "the against team opens the score")
    m.ev(13, "re-kickoff", "team", "started")
    m.keep(14)
    m.ev(15, "pass-from-hf", "team", "lost")
    for t in range(16, 20):
        m.keep(t)
    m.ev(20, "tackle-in-hf", "team", "won")
    m.keep(21); m.keep(22)
    m.ev(23, "pass-from-hf", "team", "advanced", "the for team attacks")
    m.keep(24)
    m.ev(25, "pass-from-ohf", "team", "advanced")
    m.ev(26, "pass-from-opr", "team", "kept")
    m.ev(27, "tackle-in-pr", "oteam", "won")
    m.ev(28, "tackle-in-opr", "team", "won")
    m.ev(29, "pass-from-opr", "team", "kept")
    m.ev(30, "shot", "team", "goal", "the for team equalises")
    m.ev(31, "re-kickoff", "oteam", "started")
    m.keep(32)
    m.ev(33, "pass-from-hf", "oteam", "advanced")
    m.ev(34, "tackle-in-hf", "team", "won")
    for t in range(35, 39):
        m.keep(t)
    m.ev(39, "tackle-in-ohf", "oteam", "foul", "free-kick for the for team in their half")
    m.ev(40, "take-freekick-in-hf", "team", "long", "the long free-kick reaches the penalty area")
    m.ev(40.5, "shot", "team", "goal", "the for team leads")
    m.ev(41, "re-kickoff", "oteam", "started")
    for t in range(42, 46):
        m.keep(t)
    m.ev(46, "tackle-in-ohf", "team", "won")
    for t in range(47, 52):
        m.keep(t)
    m.ev(52, "pass-from-ohf", "team", "advanced")
    m.ev(53, "pass-from-opr", "team", "lost")
    m.ev(54, "pass-from-pr", "oteam", "advanced")
    for t in range(55, 58):
        m.keep(t)
    m.ev(58, "tackle-in-ohf", "team", "won")
    for t in range(59, 64):
        m.keep(t)
    m.ev(64, "pass-from-ohf", "team", "lost")
    for t in range(65, 70):
        m.keep(t)
    m.ev(70, "tackle-in-ohf", "team", "won")
    m.keep(71); m.keep(72)
    m.ev(73, "tackle-in-hf", "oteam", "won")
    m.keep(74); m.keep(75)
    m.ev(76, "pass-from-hf", "oteam", "advanced", "the against team presses")
    m.keep(77)
    m.ev(78, "pass-from-ohf", "oteam", "advanced")
    m.ev(79, "tackle-in-pr", "team", "nothing")
    m.ev(80, "shot", "oteam", "goal", "the against team equalises")
    m.ev(81, "re-kickoff", "team", "started")
    for t in range(82, 91):
        m.keep(t)
    for e in m.events:
        sys.stdout.write(json.dumps(e) + "\n")


if __name__ == "__main__":
    main()
