# compare.py - how far two renders differ: mean absolute difference (0-255, RGB) and SSIM, optionally a diff image.
# Usage: python3 compare.py A.png B.png [--diff diff.png] [--gain 4]
import argparse, os, sys
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ left beside png.py or make_models.py
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tests', 'e2e', 'lib'))
from png import read_png  # noqa: E402  (the repo's 8-bit RGB/RGBA reader)
from make_models import png_bytes  # noqa: E402  (a small RGB PNG writer)


def load_rgb(path):
    """(h, w, 3) float64; alpha is dropped (facet and three.js both draw opaque frames here)."""
    w, h, ch, rows = read_png(path)
    return np.frombuffer(b''.join(rows), np.uint8).reshape(h, w, ch)[..., :3].astype(np.float64)


def gaussian_filter(image, sigma=1.5, size=11):
    """Separable Gaussian over the 'valid' region only, as in Wang et al.'s reference code (no edge padding)."""
    x = np.arange(size) - size // 2
    k = np.exp(-x ** 2 / (2 * sigma ** 2))
    k /= k.sum()
    rows = np.lib.stride_tricks.sliding_window_view(image, size, axis=0) @ k
    return np.lib.stride_tricks.sliding_window_view(rows, size, axis=1) @ k


def ssim(a, b, L=255.0, K1=0.01, K2=0.03):
    """Mean SSIM (Wang, Bovik, Sheikh, Simoncelli 2004) of one channel."""
    c1, c2 = (K1 * L) ** 2, (K2 * L) ** 2
    mu_a, mu_b = gaussian_filter(a), gaussian_filter(b)
    var_a = gaussian_filter(a * a) - mu_a ** 2
    var_b = gaussian_filter(b * b) - mu_b ** 2
    cov = gaussian_filter(a * b) - mu_a * mu_b
    s = ((2 * mu_a * mu_b + c1) * (2 * cov + c2)) / ((mu_a ** 2 + mu_b ** 2 + c1) * (var_a + var_b + c2))
    return float(s.mean())


def main():
    parser = argparse.ArgumentParser(description='Mean absolute difference and SSIM of two PNGs of one size.')
    parser.add_argument('a')
    parser.add_argument('b')
    parser.add_argument('--diff', help='write |A - B| times --gain as a PNG')
    parser.add_argument('--gain', type=float, default=4, help='amplification of the diff image (4)')
    args = parser.parse_args()
    a, b = load_rgb(args.a), load_rgb(args.b)
    if a.shape != b.shape:
        sys.exit(f'compare.py: {args.a} is {a.shape[1]}x{a.shape[0]}, {args.b} is {b.shape[1]}x{b.shape[0]}')
    diff = np.abs(a - b)
    # SSIM per channel, then their mean, so a hue shift counts as well as a change of brightness.
    value = np.mean([ssim(a[..., c], b[..., c]) for c in range(3)])
    print(f'mean abs diff {diff.mean():.3f}  SSIM {value:.4f}')
    if args.diff:
        with open(args.diff, 'wb') as f:
            f.write(png_bytes(np.clip(diff * args.gain, 0, 255).astype(np.uint8)))


if __name__ == '__main__':
    main()
