"""Is rviz showing the lesson yet? Pixel checks on a screenshot, and rviz's log (no rospy).

Images are H x W x 3 uint8 arrays. The colours are lesson_markers' and the .rviz files'.
"""

import numpy as np

from course_common.rviz.colours import ARENA_RGB, PALETTE

#: The .rviz files' "Background Color" (48; 48; 48): only rviz's 3D view has it.
BACKGROUND = (48, 48, 48)
MIN_BACKGROUND_RUN = 100  # px of background in a row/column of the 3D view: no widget has that
COLOUR_TOLERANCE = 40  # per channel, 0..255: rviz shades and blends what it draws
MIN_ARENA_PIXELS = 300  # the outline is ~4 x 600 px long, a few px wide
MIN_ROBOT_PIXELS = 30  # one arrow is ~45 x 8 px
# Text is drawn white, anti-aliased, in rviz's Liberation Sans: bookworm's (1.07) core is near
# 255, trixie's (2.1) is thinner and greyer (a third as many pixels reach 240). From 200 up a
# name like "robot_2" at 0.35 m is ~120 px on bookworm and ~100 on trixie; nothing else in the
# view is that light (the grid is ~70).
WHITE_MIN = 200
MIN_TEXT_PIXELS = 30
#: Log lines that are not errors of the file or the lesson: Debian's rviz asks rospack for
#: OGRE media of the `media_export` package, which Debian does not ship (nothing uses them);
#: Mesa's GLSL linker rejects the Map display's palette shader as it is first used ("active
#: samplers with a different type refer to the same texture image unit", ros2/rviz #453,
#: #459, #951: the map is drawn all the same; a test that shows a map checks its pixels).
KNOWN_NOISE = ('no such package media_export', '[librospack]: error while executing command',
               'rviz/glsl120/indexed_8bit_image.vert')


def colour_pixels(image, rgb, tolerance=COLOUR_TOLERANCE):
    """How many pixels are within tolerance (per channel) of rgb, given as 0..1 floats."""
    target = np.array([round(255 * c) for c in rgb], dtype=np.int16)
    return int((np.abs(image.astype(np.int16) - target) <= tolerance).all(axis=2).sum())


def render_area(image, background_rgb=BACKGROUND, tolerance=0):
    """The part of a screenshot that is rviz's 3D view (the widgets around it cut off).

    The rows and columns holding MIN_BACKGROUND_RUN or more background pixels bound it; an
    image without that much background gives an empty array (nothing drawn yet).
    background_rgb (0..255, within tolerance per channel): the colour that fills the view,
    the .rviz file's background unless something covers it all (a map: its free cells).
    """
    target = np.array(background_rgb, dtype=np.int16)
    background = (np.abs(image.astype(np.int16) - target) <= tolerance).all(axis=2)
    cols = np.nonzero(background.sum(axis=0) >= MIN_BACKGROUND_RUN)[0]
    rows = np.nonzero(background.sum(axis=1) >= MIN_BACKGROUND_RUN)[0]
    if cols.size == 0 or rows.size == 0:
        return image[:0, :0]
    return image[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]


def missing_colours(image, colours, min_pixels, tolerance=COLOUR_TOLERANCE):
    """The names of the colours ({name: rgb as 0..1 floats}) that fewer than min_pixels
    pixels of image show (within tolerance per channel), in the order given."""
    if min_pixels < 1:
        raise ValueError('min_pixels must be >= 1, got %r' % (min_pixels,))
    return [name for name, rgb in colours.items()
            if colour_pixels(image, rgb, tolerance) < min_pixels]


def shows_lesson(image, robots, labels):
    """True when rviz's view shows the arena, `robots` robot colours and `labels` texts.

    Texts (the robots' names, drawn in each robot's tf frame, and the convoy's gap labels)
    show that tf and every marker topic have reached rviz, not just the trails.
    """
    if robots < 0 or labels < 0:
        raise ValueError('robots and labels must be >= 0, got %r and %r' % (robots, labels))
    view = render_area(image)
    if view.size == 0 or colour_pixels(view, ARENA_RGB) < MIN_ARENA_PIXELS:
        return False
    seen = sum(colour_pixels(view, rgb) >= MIN_ROBOT_PIXELS for rgb in PALETTE)
    text = int((view >= WHITE_MIN).all(axis=2).sum())
    return seen >= min(robots, len(PALETTE)) and text >= labels * MIN_TEXT_PIXELS


def error_lines(log_text):
    """The lines of an rviz log that report an error, the known Debian noise left out."""
    return [line for line in log_text.splitlines()
            if ('ERROR' in line or 'Error' in line or 'FATAL' in line)
            and not any(noise in line for noise in KNOWN_NOISE)]
