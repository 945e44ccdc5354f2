# imgdiff.py - how two renders of a benchmark scene differ, as one JSON line (docs/BENCHMARK.md, section 10).
# Usage: python3 imgdiff.py A.png B.png [--diff DIFF.png]
import argparse, json, os, sys
import numpy as np

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tests', 'e2e', 'lib'))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'appearance'))
from png import read_png  # noqa: E402  (the repo's 8-bit RGB/RGBA reader)
from make_models import png_bytes  # noqa: E402  (a small RGB PNG writer)

CLEAR = np.array([26, 26, 38])  # the scenes' clear colour
THRESHOLD = 8  # a pixel differs when its largest channel difference exceeds this


def load_rgb(path):
    width, height, channels, rows = read_png(path)
    return np.frombuffer(b''.join(rows), np.uint8).reshape(height, width, channels)[:, :, :3].astype(np.int32)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('a')
    parser.add_argument('b')
    parser.add_argument('--diff', help='write the per-pixel largest difference, times 4, as a grey PNG')
    args = parser.parse_args()
    a, b = load_rgb(args.a), load_rgb(args.b)
    if a.shape != b.shape:
        sys.exit(f'imgdiff.py: {args.a} is {a.shape[1]}x{a.shape[0]}, {args.b} is {b.shape[1]}x{b.shape[0]}')
    difference = np.abs(a - b)
    largest = difference.max(axis=2)
    covered_a, covered_b = (a != CLEAR).any(axis=2), (b != CLEAR).any(axis=2)
    union = np.count_nonzero(covered_a | covered_b)
    result = {
        'pixels': int(largest.size),
        'mean_abs': round(float(difference.mean()), 4),
        'max_abs': int(difference.max()),
        'over_threshold': round(float(np.count_nonzero(largest > THRESHOLD)) / largest.size, 6),
        'coverage_iou': round(np.count_nonzero(covered_a & covered_b) / union, 6) if union else 1.0,
    }
    if args.diff:
        grey = np.minimum(largest * 4, 255).astype(np.uint8)
        with open(args.diff, 'wb') as f:
            f.write(png_bytes(np.repeat(grey[:, :, None], 3, axis=2)))
    print(json.dumps(result, separators=(',', ':')))


if __name__ == '__main__':
    main()
