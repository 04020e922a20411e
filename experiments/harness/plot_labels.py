"""Labels beside the points of a matplotlib axes that overlap neither each other nor the points
(plot_suite.py's Pareto fronts and scatter plots): each label at the first offset where it fits,
with a leader line when it had to move away. Split from plot_suite.py."""
import matplotlib
import matplotlib.text
import matplotlib.transforms


def overlaps(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


# Label positions tried in turn (points from the point): beside it, then further away with a
# leader line.
OFFSETS = [(4, 3), (4, -9), (-4, 3), (-4, -9), (4, 12), (-4, 12), (4, -18), (-4, -18)] + [
    (sx * r, sy * r * 0.7) for r in (20, 32, 46, 60) for sx, sy in
    ((1, 1), (1, -1), (-1, 1), (-1, -1))]


def place_labels(ax, points, fontsize=6, obstacles=()):
    """Labels beside points, each at the first offset (OFFSETS) where it stays inside the axes and
    overlaps no label placed before and no point (greedy, in the given order; a leader line when
    it had to move away); where nowhere is free, at the first offset. Obstacles: (x, y) of the
    unlabelled points, and the texts already in the axes."""
    renderer = ax.figure.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    taken = []
    for x, y in [p[:2] for p in points] + list(obstacles):
        px, py = ax.transData.transform((x, y))
        taken.append(matplotlib.transforms.Bbox([[px - 3, py - 3], [px + 3, py + 3]]))
    taken += [t.get_window_extent(renderer) for t in ax.texts]  # e.g. the oracle's time
    done = set()
    for x, y, text in points:
        if (x, y, text) in done:
            continue  # items with the same result (e.g. lossless storages) are labelled once
        done.add((x, y, text))
        for dx, dy in OFFSETS:
            far = abs(dx) > 10 or abs(dy) > 12
            t = ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points",
                            fontsize=fontsize, ha="left" if dx > 0 else "right",
                            va="bottom" if dy > 0 else "top",
                            arrowprops=dict(arrowstyle="-", color="0.4", linewidth=0.5,
                                            shrinkA=0, shrinkB=2) if far else None)
            t.update_positions(renderer)
            box = matplotlib.text.Text.get_window_extent(t, renderer)  # the text, not its line
            if (box.x0 >= frame.x0 and box.x1 <= frame.x1 and box.y0 >= frame.y0 and
                    box.y1 <= frame.y1 and not any(overlaps(box, b) for b in taken)):
                break
            t.remove()
        else:
            t = ax.annotate(text, (x, y), xytext=OFFSETS[0], textcoords="offset points",
                            fontsize=fontsize)
            box = t.get_window_extent(renderer)
        taken.append(box)
