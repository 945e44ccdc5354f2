# video.py - checks an MP4 or WebM file with FFmpeg's own tools: codec, size, frame count and rate, first frame.
# video.py FILE CODEC WIDTH HEIGHT FRAMES RATE [FIRST_FRAME.png]: exits non-zero, saying why, unless the video is
# that; with a PNG, its first frame decoded by ffmpeg must match the PNG within a mean absolute difference of 4
# (YUV 4:2:0 and the codec's loss cost a little, a wrong colour conversion or frame far more).
import json, os, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png import read_png  # noqa: E402


def probe(path):
    out = subprocess.run(['ffprobe', '-v', 'error', '-count_frames', '-select_streams', 'v:0', '-show_entries',
                          'stream=codec_name,width,height,nb_read_frames,r_frame_rate,pix_fmt:format=format_name',
                          '-of', 'json', path], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f'{path}: ffprobe cannot read it: {out.stderr.strip()}')
    info = json.loads(out.stdout)
    return info['streams'][0], info['format']['format_name']


def first_frame(path, width, height):
    with tempfile.TemporaryDirectory() as folder:
        png = os.path.join(folder, 'first.png')
        subprocess.run(['ffmpeg', '-v', 'error', '-i', path, '-frames:v', '1', '-vf', f'crop={width}:{height}:0:0',
                        '-pix_fmt', 'rgb24', png], check=True)
        return read_png(png)


if __name__ == '__main__':
    path, codec = sys.argv[1], sys.argv[2]
    width, height, frames = (int(a) for a in sys.argv[3:6])
    rate = sys.argv[6]
    stream, container = probe(path)
    got = (stream['codec_name'], stream['width'], stream['height'], int(stream['nb_read_frames']),
           stream['r_frame_rate'], stream['pix_fmt'])
    # 4:2:0 needs even sizes: an odd one gains a column or row.
    want = (codec, width + width % 2, height + height % 2, frames, rate, 'yuv420p')
    if got != want:
        sys.exit(f'{container}: {got}; wanted {want}')
    note = ''
    if len(sys.argv) > 7:
        w, h, ch, rows = read_png(sys.argv[7])
        _, _, _, video = first_frame(path, width, height)
        total = sum(abs(rows[y][x * ch + c] - video[y][x * 3 + c]) for y in range(h) for x in range(w) for c in range(3))
        mean = total / (w * h * 3)
        if mean > 4:
            sys.exit(f'first frame differs from {sys.argv[7]}: mean absolute difference {mean:.2f} > 4')
        note = f', first frame within {mean:.2f} of the PNG'
    print(f'{codec} in {container.split(",")[0]}, {got[1]}x{got[2]}, {frames} frames at {rate}{note}')
