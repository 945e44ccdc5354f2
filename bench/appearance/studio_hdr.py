# studio_hdr.py - writes a neutral "studio" (or a constant) equirectangular environment as a Radiance .hdr file.
# Usage: python3 studio_hdr.py OUT.hdr [--width W] [--uniform V]
# Layout as three.js maps an equirect: top row straight up, the centre column towards +X, a quarter to its right +Z.
import argparse
import numpy as np


def directions(width, height):
    """Unit world directions of the pixel centres, (height, width, 3), and their elevation."""
    u = (np.arange(width) + 0.5) / width
    v = 1 - (np.arange(height) + 0.5) / height           # 1 at the top row
    phi = (u - 0.5) * 2 * np.pi                            # azimuth, 0 towards +X, +pi/2 towards +Z
    elev = (v - 0.5) * np.pi
    phi, elev = np.meshgrid(phi, elev)
    d = np.stack([np.cos(elev) * np.cos(phi), np.sin(elev), np.cos(elev) * np.sin(phi)], axis=-1)
    return d, elev


def smoothstep(e0, e1, x):
    t = np.clip((x - e0) / (e1 - e0), 0, 1)
    return t * t * (3 - 2 * t)


def softbox(d, azimuth, elevation, half_w, half_h, soft, radiance):
    """A rectangle of constant radiance seen from the centre, angular half sizes in degrees, edges soft over `soft`."""
    az, el = np.radians(azimuth), np.radians(elevation)
    c = np.array([np.cos(el) * np.cos(az), np.sin(el), np.cos(el) * np.sin(az)])  # towards the box
    t = np.cross([0.0, 1.0, 0.0], c)
    t /= np.linalg.norm(t)
    b = np.cross(c, t)
    front = d @ c
    a = np.degrees(np.arctan2(d @ t, front))
    h = np.degrees(np.arctan2(d @ b, front))
    mask = smoothstep(half_w + soft, half_w, np.abs(a)) * smoothstep(half_h + soft, half_h, np.abs(h)) * (front > 0)
    return radiance * mask


def studio(width, height):
    d, elev = directions(width, height)
    # Soft grey walls: brighter towards the top, a darker floor, the horizon blended over about 10 degrees.
    wall = 0.3 + 0.3 * np.sin(np.clip(elev, 0, None))
    floor = 0.1
    base = floor + (wall - floor) * smoothstep(-np.radians(5), np.radians(5), elev)
    light = (softbox(d, 120, 35, 22, 14, 6, 12.0)     # key: front-left (-X+Z), above
             + softbox(d, -15, 15, 16, 12, 6, 4.0)     # fill: right, lower and dimmer
             + softbox(d, 0, 70, 30, 10, 8, 6.0))     # overhead strip, leaning right
    return np.repeat((base + light)[..., None], 3, axis=-1)


def write_hdr(path, rgb):
    """Flat (not run-length encoded) RGBE scanlines, which every reader accepts."""
    height, width, _ = rgb.shape
    m = rgb.max(axis=-1)
    mantissa, exponent = np.frexp(m)
    scale = np.where(m > 1e-32, mantissa * 256 / np.where(m > 1e-32, m, 1), 0)
    rgbe = np.zeros((height, width, 4), np.uint8)
    rgbe[..., :3] = np.clip(np.floor(rgb * scale[..., None]), 0, 255)
    rgbe[..., 3] = np.where(m > 1e-32, exponent + 128, 0)
    with open(path, 'wb') as f:
        f.write(f'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n'.encode('ascii'))
        f.write(rgbe.tobytes())


def main():
    parser = argparse.ArgumentParser(description='Writes an equirectangular studio environment (.hdr).')
    parser.add_argument('output')
    parser.add_argument('--width', type=int, default=256, help='the height is half of it')
    parser.add_argument('--uniform', type=float, help='a constant radiance everywhere (furnace tests)')
    args = parser.parse_args()
    width, height = args.width, args.width // 2
    if args.uniform is not None:
        rgb = np.full((height, width, 3), args.uniform)
    else:
        rgb = studio(width, height)
    write_hdr(args.output, rgb)
    _, elev = directions(width, height)
    weight = np.cos(elev)  # solid angle of an equirect pixel
    mean = (rgb[..., 0] * weight).sum() / weight.sum()
    print(f'{args.output}: {width}x{height}, mean radiance {mean:.3f}, max {rgb.max():.2f}')


if __name__ == '__main__':
    main()
