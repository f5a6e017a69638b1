"""PNG figures of a convoy report (matplotlib, headless Agg backend): trails and gaps."""
from course_common.arena import WORLD_SIZE_M


def _pyplot():
    import matplotlib
    matplotlib.use('Agg')  # no display needed: the demo runs headless
    import matplotlib.pyplot as plt
    return plt


def plot_gaps(path, report, tolerance_m):
    """Writes a PNG of each follower's distance to its leader over time (convoy.report)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
    for pair in report.pairs:
        ax.plot([t for t, _ in pair.gaps], [g for _, g in pair.gaps],
                label='%s to %s' % (pair.follower, pair.leader), linewidth=1.2)
    ax.axhline(tolerance_m, color='grey', linestyle='--', linewidth=1,
               label='tolerance %.1f m' % tolerance_m)
    ax.axhline(report.threshold_m, color='grey', linestyle=':', linewidth=1,
               label='caught up %.1f m' % report.threshold_m)
    ax.set_xlabel('time since every robot was up (s)')
    ax.set_ylabel('distance to its leader (m)')
    ax.set_title('Convoy: each follower chasing its leader')
    ax.grid(True, alpha=0.3)
    ax.legend(loc='upper right', fontsize='small')
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_trails(path, report):
    """Writes a PNG of every robot's path in the turtlesim world (x, y in metres), a circle
    where it started and a triangle where it ended."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6, 6), dpi=100)
    for robot, samples in report.tracks.items():
        xs, ys = [s[1] for s in samples], [s[2] for s in samples]
        line, = ax.plot(xs, ys, label=robot, linewidth=1.2)
        if samples:
            ax.plot(xs[:1], ys[:1], 'o', color=line.get_color())
            ax.plot(xs[-1:], ys[-1:], '^', color=line.get_color())
    ax.set_xlim(0.0, WORLD_SIZE_M)
    ax.set_ylim(0.0, WORLD_SIZE_M)
    ax.set_aspect('equal')
    ax.set_xlabel('x (m)')
    ax.set_ylabel('y (m)')
    ax.set_title('Convoy trails over %.0f s (o start, ^ end)' % report.duration_s)
    ax.grid(True, alpha=0.3)
    ax.legend(loc='upper right', fontsize='small')
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
