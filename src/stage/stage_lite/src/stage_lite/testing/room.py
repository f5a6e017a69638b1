"""A square room as a floor plan, for tests' small worlds (no rospy)."""


def write_room_pgm(path, pixels=100):
    """Writes a pixels x pixels binary PGM: free inside, a one-pixel wall on every border.
    With `size [10 10 1]` it is a 10 m room with 0.1 m walls."""
    img = bytearray(b'\xff' * pixels * pixels)
    for i in range(pixels):
        for j in (0, pixels - 1):
            img[i * pixels + j] = img[j * pixels + i] = 0
    with open(path, 'wb') as f:
        f.write(b'P5 %d %d 255\n' % (pixels, pixels) + bytes(img))
