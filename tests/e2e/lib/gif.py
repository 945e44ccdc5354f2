# gif.py - gif_info(): the block structure of a GIF in plain python3, for the e2e checks of animations.
import sys


def gif_info(path):
    """(width, height, frames, loops, delays, colours): image count, NETSCAPE2.0 present, the set of frame delays
    in centiseconds and the number of distinct global palette entries."""
    data = open(path, 'rb').read()
    if data[:6] != b'GIF89a':
        sys.exit(f'{path}: not a GIF89a file')
    width, height, flags = int.from_bytes(data[6:8], 'little'), int.from_bytes(data[8:10], 'little'), data[10]
    size = 2 ** ((flags & 7) + 1) if flags & 0x80 else 0
    colours = len({data[13 + 3 * i:16 + 3 * i] for i in range(size)})
    pos, frames, loops, delays = 13 + 3 * size, 0, False, set()

    def skip_blocks(pos):
        while data[pos]:
            pos += data[pos] + 1
        return pos + 1

    while data[pos] != 0x3B:
        if data[pos] == 0x21:
            label = data[pos + 1]
            if label == 0xFF and data[pos + 3:pos + 14] == b'NETSCAPE2.0':
                loops = True
            if label == 0xF9:
                delays.add(int.from_bytes(data[pos + 4:pos + 6], 'little'))
            pos = skip_blocks(pos + 2)
        elif data[pos] == 0x2C:
            frames += 1
            local = data[pos + 9]
            pos += 10 + (3 * 2 ** ((local & 7) + 1) if local & 0x80 else 0)
            pos = skip_blocks(pos + 1)
        else:
            sys.exit(f'{path}: unexpected block {data[pos]:#x} at byte {pos}')
    return width, height, frames, loops, delays, colours


if __name__ == '__main__':
    # gif.py FILE WIDTH HEIGHT FRAMES DELAY: exits non-zero, saying why, unless the GIF is that.
    w, h, n, loops, delays, colours = gif_info(sys.argv[1])
    want = tuple(int(a) for a in sys.argv[2:6])
    got = (w, h, n, min(delays) if delays else -1)
    if got != want or not loops or len(delays) != 1 or colours <= 16:
        sys.exit(f'{w}x{h}, {n} frames, delays {sorted(delays)}, loops {loops}, {colours} colours; wanted {want}')
    print(f'{w}x{h}, {n} frames of {want[3]} cs, looping, {colours} colours')
