"""Stage's `rasterize` (examples/ctrl/rasterize.cc): at start-up, prints its model's outline
as a 40 x 20 raster of the model's size ('O' where a block's edge passes), top row first."""

WIDTH, HEIGHT = 40, 20


def init(model, args):
    _, size = model.get_geom()
    # the plugin's cell sizes: a double over a float, in double
    data = model.rasterize(WIDTH, HEIGHT, size[0] / float(WIDTH), size[1] / float(HEIGHT))
    lines = ['', '[Rasterize] Raster of model "%s":' % model.token]
    for y in range(HEIGHT - 1, -1, -1):
        row = data[y * WIDTH:(y + 1) * WIDTH]
        lines.append('[Rasterize] ' + ''.join('O' if v else '.' for v in row))
    lines.append('[Rasterize] Done')
    print('\n'.join(lines), flush=True)


