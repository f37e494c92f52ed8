#!/usr/bin/env python3
"""Writes the cascade training / testing scenes of this directory.

Each scene is a room with washbasins, wastebaskets and stairs of varied
sizes and placements (against walls, in corners, free-standing), furniture
as distractors (cabinets, tables, chairs, boxes as large as a wastebasket,
pillars) and stop-and-scan poses that see the objects from about 0.8 m to
5 m at many bearings. Scenes differ by seed; train_* are for training,
val_* for choosing detector settings, test_* are held out. Deterministic: python3 make_scenes.py rewrites the
same files. Lengths m, angles deg (docs/design.md scene format).
"""
import math
import random

SCENES = [
    # name, seed, room width, room depth
    ("train_a", 11, 10.0, 8.0),
    ("train_b", 12, 11.0, 7.5),
    ("train_c", 13, 9.0, 8.5),
    ("train_d", 14, 12.0, 8.0),
    ("train_e", 15, 8.5, 7.0),
    ("train_f", 16, 10.0, 9.0),
    ("train_g", 17, 11.5, 8.5),
    ("train_h", 18, 9.5, 7.5),
    ("train_i", 19, 12.0, 9.0),
    ("train_j", 20, 10.5, 7.0),
    ("train_k", 21, 9.0, 9.0),
    ("train_l", 22, 11.0, 8.0),
    ("train_m", 23, 10.0, 7.5),
    ("train_n", 24, 12.0, 8.5),
    ("train_o", 25, 8.5, 8.0),
    ("train_p", 26, 10.5, 9.0),
    ("train_q", 27, 11.5, 7.5),
    ("train_r", 28, 9.5, 8.5),
    ("train_s", 29, 10.0, 8.0),
    ("train_t", 30, 11.0, 9.0),
    ("test_a", 101, 10.5, 8.0),
    ("test_b", 102, 9.5, 9.0),
    ("test_c", 103, 11.0, 8.0),
    # Validation: neither trained on nor held out; detector settings are
    # chosen on these (scores on train_* flatter a change: the cascades
    # learnt those very objects).
    ("val_a", 201, 10.0, 8.5),
    ("val_b", 202, 11.5, 8.0),
    ("val_c", 203, 9.5, 8.0),
    # Added with the shape models: more validation scenes, and held-out
    # scenes no setting was ever looked at on before the final choice.
    ("val_d", 204, 10.5, 8.5),
    ("val_e", 205, 9.0, 8.0),
    ("val_f", 206, 11.0, 9.0),
    ("test_d", 104, 10.0, 9.0),
    ("test_e", 105, 11.5, 8.5),
    ("test_f", 106, 9.0, 7.5),
    # Added with the segment candidates: six more validation scenes (more
    # pillars, boxes and far flights to choose settings on).
    ("val_g", 207, 10.0, 9.0),
    ("val_h", 208, 11.5, 8.5),
    ("val_i", 209, 9.5, 7.5),
    ("val_j", 210, 10.5, 8.0),
    ("val_k", 211, 12.0, 8.5),
    ("val_l", 212, 9.0, 8.5),
    # Added for the shape forests (train_u..an): twenty more training scenes,
    # twice the flights of stairs to learn from (one flight per scene).
    ("train_u", 31, 9.5, 7.5),
    ("train_v", 32, 11.0, 7.0),
    ("train_w", 33, 10.5, 7.5),
    ("train_x", 34, 8.5, 8.0),
    ("train_y", 35, 8.5, 8.0),
    ("train_z", 36, 8.5, 7.0),
    ("train_aa", 37, 10.0, 8.5),
    ("train_ab", 38, 9.0, 7.5),
    ("train_ac", 39, 10.5, 9.0),
    ("train_ad", 40, 10.5, 8.0),
    ("train_ae", 41, 12.0, 7.0),
    ("train_af", 42, 11.5, 7.5),
    ("train_ag", 43, 9.0, 7.0),
    ("train_ah", 44, 9.5, 8.5),
    ("train_ai", 45, 9.0, 8.0),
    ("train_aj", 46, 10.5, 7.5),
    ("train_ak", 47, 10.5, 7.0),
    ("train_al", 48, 8.5, 7.5),
    ("train_am", 49, 11.0, 8.0),
    ("train_an", 50, 9.5, 8.0),
    # Six more held-out scenes, added after the settings of the round with
    # the parallel passes were fixed (issue 4's figure on twice the views).
    ("test_g", 107, 10.0, 8.5),
    ("test_h", 108, 11.5, 7.5),
    ("test_i", 109, 9.5, 8.5),
    ("test_j", 110, 12.0, 8.0),
    ("test_k", 111, 9.0, 7.5),
    ("test_l", 112, 10.5, 9.0),
]


def fmt(v):
    return ("%.3f" % v).rstrip("0").rstrip(".") if isinstance(v, float) else str(v)


def vec(vs):
    return "[" + ", ".join(fmt(float(v)) for v in vs) + "]"


class Scene:
    def __init__(self, name, seed, W, H):
        self.name, self.W, self.H = name, W, H
        self.r = random.Random(seed)
        self.ceiling = round(self.r.uniform(2.5, 2.9), 2)
        self.lines = []
        self.footprints = []  # (x, y, radius) keep-out circles for poses
        self.counts = {}

    def add(self, comment, text, fp):
        self.lines.append("  # " + comment)
        self.lines.append(text)
        self.footprints.extend(fp)

    def box(self, label, c, s, yaw=0.0):
        return "  - {label: %s, box: {center: %s, size: %s, yaw: %s}}" % (
            label, vec(c), vec(s), fmt(float(yaw)))

    def free(self, x, y, rad):
        if not (0.1 < x < self.W - 0.1 and 0.1 < y < self.H - 0.1):
            return False
        for (fx, fy, fr) in self.footprints:
            if math.hypot(x - fx, y - fy) < rad + fr + 0.25:
                return False
        return True

    # --- objects ---------------------------------------------------------
    def walls(self):
        W, H, h = self.W, self.H, self.ceiling
        self.lines.append("  # outer walls")
        self.lines.append(self.box("wall", [W / 2, 0.05, h / 2], [W, 0.1, h]))
        self.lines.append(self.box("wall", [W / 2, H - 0.05, h / 2], [W, 0.1, h]))
        self.lines.append(self.box("wall", [0.05, H / 2, h / 2], [0.1, H, h]))
        self.lines.append(self.box("wall", [W - 0.05, H / 2, h / 2], [0.1, H, h]))

    def wall_spot(self, depth, width):
        """A point in front of a random wall: centre x, y and the yaw (deg)
        of the wall's inward normal."""
        for _ in range(200):
            side = self.r.randrange(4)
            if side == 0:
                x, y, yaw = self.r.uniform(0.6, self.W - 0.6), 0.1 + depth / 2, 90
            elif side == 1:
                x, y, yaw = self.r.uniform(0.6, self.W - 0.6), self.H - 0.1 - depth / 2, -90
            elif side == 2:
                x, y, yaw = 0.1 + depth / 2, self.r.uniform(0.6, self.H - 0.6), 0
            else:
                x, y, yaw = self.W - 0.1 - depth / 2, self.r.uniform(0.6, self.H - 0.6), 180
            if self.free(x, y, max(depth, width) / 2):
                return x, y, yaw
        raise RuntimeError("no wall spot")

    def washbasin(self):
        w = self.r.uniform(0.40, 0.62)
        d = self.r.uniform(0.35, 0.50)
        t = self.r.uniform(0.12, 0.19)
        top = self.r.uniform(0.78, 0.92)
        x, y, yaw = self.wall_spot(d, w)
        a = math.radians(yaw)
        nx, ny = math.cos(a), math.sin(a)  # into the room
        # basin box: its depth along the wall normal
        size = [d, w, t]
        basin = "      - {box: {center: %s, size: %s, yaw: %s}}" % (
            vec([x, y, top - t / 2]), vec(size), fmt(float(yaw)))
        pr = self.r.uniform(0.06, 0.10)
        back = d / 2 - pr - self.r.uniform(0.02, 0.10)  # pedestal near the wall
        px, py = x - nx * back, y - ny * back
        ph = top - t
        pedestal = "      - {cylinder: {center: %s, radius: %s, height: %s}}" % (
            vec([px, py, ph / 2]), fmt(pr), fmt(ph))
        self.add("washbasin %.2f x %.2f, top %.2f m" % (w, d, top),
                 "  - label: washbasin\n    parts:\n" + basin + "\n" + pedestal,
                 [(x, y, max(w, d) / 2)])

    def wastebasket(self, where):
        rad = self.r.uniform(0.12, 0.20)
        h = self.r.uniform(0.30, 0.50)
        for _ in range(300):
            if where == "wall":
                x, y, _ = self.wall_spot(2 * rad + self.r.uniform(0.0, 0.08), 2 * rad)
            elif where == "corner":
                cx = self.r.choice([0.1 + rad + 0.02, self.W - 0.1 - rad - 0.02])
                cy = self.r.choice([0.1 + rad + 0.02, self.H - 0.1 - rad - 0.02])
                x, y = cx, cy
            else:
                x, y = self.r.uniform(1.0, self.W - 1.0), self.r.uniform(1.0, self.H - 1.0)
            if self.free(x, y, rad):
                break
        else:
            return
        self.add("wastebasket r %.2f h %.2f (%s)" % (rad, h, where),
                 "  - {label: wastebasket, cylinder: {center: %s, radius: %s, height: %s}}" % (
                     vec([x, y, h / 2]), fmt(rad), fmt(h)),
                 [(x, y, rad)])

    def stairs(self):
        steps = self.r.randint(3, 7)
        rise = self.r.uniform(0.15, 0.19)
        run = self.r.uniform(0.25, 0.32)
        width = self.r.uniform(0.9, 1.6)
        L = steps * run
        for _ in range(300):
            # climbing toward a wall: origin at the foot, L before the wall
            side = self.r.randrange(4)
            if side == 0:
                ox, oy, yaw = self.r.uniform(width / 2 + 0.2, self.W - width / 2 - 0.2), 0.1 + L, -90
            elif side == 1:
                ox, oy, yaw = self.r.uniform(width / 2 + 0.2, self.W - width / 2 - 0.2), self.H - 0.1 - L, 90
            elif side == 2:
                ox, oy, yaw = 0.1 + L, self.r.uniform(width / 2 + 0.2, self.H - width / 2 - 0.2), 180
            else:
                ox, oy, yaw = self.W - 0.1 - L, self.r.uniform(width / 2 + 0.2, self.H - width / 2 - 0.2), 0
            a = math.radians(yaw)
            cx, cy = ox + math.cos(a) * L / 2, oy + math.sin(a) * L / 2
            if self.free(cx, cy, max(L, width) / 2):
                break
        self.add("stairs: %d steps, rise %.3f, run %.3f, width %.2f" % (steps, rise, run, width),
                 "  - {label: stairs, stairs: {origin: %s, yaw: %s, steps: %d, rise: %s, run: %s, width: %s}}" % (
                     vec([ox, oy]), fmt(float(yaw)), steps, fmt(rise), fmt(run), fmt(width)),
                 [(cx, cy, max(L, width) / 2)])

    def cabinet(self):
        w, d, h = self.r.uniform(0.5, 1.3), self.r.uniform(0.35, 0.6), self.r.uniform(0.7, 1.9)
        x, y, yaw = self.wall_spot(d, w)
        self.add("cabinet", self.box("obstacle", [x, y, h / 2], [d, w, h], yaw), [(x, y, max(w, d) / 2)])

    def small_box(self):
        s = [self.r.uniform(0.25, 0.45), self.r.uniform(0.25, 0.45), self.r.uniform(0.3, 0.5)]
        for _ in range(300):
            x, y = self.r.uniform(0.5, self.W - 0.5), self.r.uniform(0.5, self.H - 0.5)
            if self.free(x, y, max(s[0], s[1]) * 0.75):
                break
        yaw = self.r.uniform(0, 90)
        self.add("box", self.box("obstacle", [x, y, s[2] / 2], s, yaw), [(x, y, max(s[0], s[1]) * 0.75)])

    def table(self, small=False):
        if small:  # side table
            w, d, h = self.r.uniform(0.4, 0.6), self.r.uniform(0.4, 0.6), self.r.uniform(0.5, 0.7)
        else:
            w, d, h = self.r.uniform(0.8, 1.6), self.r.uniform(0.6, 0.9), self.r.uniform(0.70, 0.76)
        for _ in range(300):
            x, y = self.r.uniform(1.2, self.W - 1.2), self.r.uniform(1.2, self.H - 1.2)
            if self.free(x, y, max(w, d) / 2 + 0.1):
                break
        yaw = self.r.choice([0, 90, self.r.uniform(0, 180)])
        a = math.radians(yaw)
        parts = ["      - {box: {center: %s, size: %s, yaw: %s}}" % (
            vec([x, y, h - 0.025]), vec([w, d, 0.05]), fmt(float(yaw)))]
        for sx in (-1, 1):
            for sy in (-1, 1):
                lx, ly = sx * (w / 2 - 0.05), sy * (d / 2 - 0.05)
                px = x + lx * math.cos(a) - ly * math.sin(a)
                py = y + lx * math.sin(a) + ly * math.cos(a)
                parts.append("      - {box: {center: %s, size: [0.05, 0.05, %s], yaw: %s}}" % (
                    vec([px, py, (h - 0.05) / 2]), fmt(h - 0.05), fmt(float(yaw))))
        self.add("side table" if small else "table", "  - label: obstacle\n    parts:\n" + "\n".join(parts), [(x, y, max(w, d) / 2 + 0.1)])

    def chair(self):
        for _ in range(300):
            x, y = self.r.uniform(0.8, self.W - 0.8), self.r.uniform(0.8, self.H - 0.8)
            if self.free(x, y, 0.35):
                break
        yaw = self.r.uniform(0, 360)
        a = math.radians(yaw)
        s = 0.44
        parts = ["      - {box: {center: %s, size: [0.44, 0.44, 0.05], yaw: %s}}" % (vec([x, y, 0.45]), fmt(yaw))]
        bx, by = x - math.cos(a) * 0.2, y - math.sin(a) * 0.2
        parts.append("      - {box: {center: %s, size: [0.04, 0.44, 0.45], yaw: %s}}" % (vec([bx, by, 0.7]), fmt(yaw)))
        for sx in (-1, 1):
            for sy in (-1, 1):
                lx, ly = sx * (s / 2 - 0.03), sy * (s / 2 - 0.03)
                px = x + lx * math.cos(a) - ly * math.sin(a)
                py = y + lx * math.sin(a) + ly * math.cos(a)
                parts.append("      - {box: {center: %s, size: [0.035, 0.035, 0.42], yaw: %s}}" % (vec([px, py, 0.21]), fmt(yaw)))
        self.add("chair", "  - label: obstacle\n    parts:\n" + "\n".join(parts), [(x, y, 0.35)])

    def pillar(self):
        for _ in range(300):
            x, y = self.r.uniform(1.5, self.W - 1.5), self.r.uniform(1.5, self.H - 1.5)
            if self.free(x, y, 0.3):
                break
        r = self.r.uniform(0.12, 0.25)
        self.add("pillar", "  - {label: obstacle, cylinder: {center: %s, radius: %s, height: %s}}" % (
            vec([x, y, self.ceiling / 2]), fmt(r), fmt(self.ceiling)), [(x, y, r)])

    # --- poses -----------------------------------------------------------
    def trajectory(self, n):
        poses = []
        tries = 0
        while len(poses) < n and tries < 20000:
            tries += 1
            x, y = self.r.uniform(0.6, self.W - 0.6), self.r.uniform(0.6, self.H - 0.6)
            if any(math.hypot(x - fx, y - fy) < fr + 0.55 for (fx, fy, fr) in self.footprints):
                continue
            if any(math.hypot(x - px, y - py) < 1.0 for (px, py, _) in poses):
                continue
            yaw = self.r.choice([0, 45, 90, 135, 180, 225, 270, 315]) + self.r.uniform(-20, 20)
            poses.append((x, y, yaw))
        return poses

    def text(self, poses):
        out = ["# %s: cascade %s scene (datasets/cascade-scenes/make_scenes.py)" % (
            self.name, "training" if self.name.startswith("train")
            else "validation" if self.name.startswith("val") else "held-out test"),
            "name: %s" % self.name,
            "bounds: %s" % vec([0, 0, self.W, self.H]),
            "ceiling_height: %s" % fmt(self.ceiling),
            "objects:"]
        out += self.lines
        out.append("odometry: {trans_noise: 0.0, rot_noise_deg_per_m: 0.0, rot_bias_deg_per_m: 0.0}")
        out.append("trajectory:")
        for (x, y, yaw) in poses:
            out.append("  - %s" % vec([x, y, yaw]))
        return "\n".join(out) + "\n"


def make(name, seed, W, H):
    s = Scene(name, seed, W, H)
    s.walls()
    s.stairs()
    for _ in range(3):
        s.washbasin()
    for where in ("wall", "corner", "free", "free", "wall"):
        s.wastebasket(where)
    for _ in range(2):
        s.cabinet()
    for _ in range(2):
        s.table()
    s.table(small=True)
    for _ in range(4):
        s.chair()
    for _ in range(2):
        s.small_box()
    s.pillar()
    poses = s.trajectory(26)
    with open("%s.yaml" % name, "w") as f:
        f.write(s.text(poses))


if __name__ == "__main__":
    for sc in SCENES:
        make(*sc)
