#!/usr/bin/python3
"""Compares FITS images of one scene from GYOTO and from grtrace (tests/benchmarks/peers/gyoto_compare.sh).

Takes: a JSON file listing runs {"name", "code" ("gyoto" | "grtrace"), "fits", "seconds", "threads"}, where each
code's last run is its converged reference. Returns (prints): each run's error against its own code's reference (the
largest pixel difference over the reference's peak, and the relative difference of the image's sum), its time per
pixel, and the two references against each other (the scenes match where they agree); writes a PNG of both
references and their difference. Assumes both codes wrote NAXIS1 = i, NAXIS2 = j (GYOTO's layout).
"""
import json
import sys

import numpy as np


def read_fits(path):
    """The primary HDU's image of a FITS file (2-D, or 3-D with one plane: GYOTO's), as float64."""
    data = open(path, 'rb').read()
    cards, offset = {}, 0
    while True:
        block = data[offset:offset + 2880]
        if len(block) < 2880:
            raise ValueError(f'{path}: no END card: not a FITS file')
        offset += 2880
        ended = False
        for k in range(36):
            card = block[80 * k:80 * k + 80].decode('ascii', 'replace')
            if card[:8].strip() == 'END':
                ended = True
                break
            if card[8:10] == '= ':
                cards[card[:8].strip()] = card[10:].split('/')[0].strip()
        if ended:
            break
    kinds = {'-64': '>f8', '-32': '>f4'}
    if cards.get('BITPIX') not in kinds:
        raise ValueError(f'{path}: BITPIX {cards.get("BITPIX")} is not a floating-point image')
    shape = [int(cards[f'NAXIS{i + 1}']) for i in range(int(cards['NAXIS']))][::-1]
    image = np.frombuffer(data, dtype=kinds[cards['BITPIX']], count=int(np.prod(shape)), offset=offset)
    image = image.astype(np.float64).reshape(shape)
    while image.ndim > 2 and image.shape[0] == 1:
        image = image[0]
    return image


def main(runs_json, png):
    runs = json.load(open(runs_json))
    images = {r['name']: read_fits(r['fits']) for r in runs}
    reference = {}
    for r in runs:  # each code's last run
        reference[r['code']] = r['name']
    rows = []
    for r in runs:
        ref = images[reference[r['code']]]
        im = images[r['name']]
        if im.shape != ref.shape:
            raise ValueError(f'{r["name"]}: {im.shape} pixels, its reference {ref.shape}')
        if not np.all(np.isfinite(im)):
            raise ValueError(f'{r["name"]}: non-finite pixels')
        pixels = im.size
        rows.append({
            'name': r['name'], 'code': r['code'],
            'max_error': float(np.abs(im - ref).max() / ref.max()),
            'flux_error': float(abs(im.sum() / ref.sum() - 1.0)),
            'seconds': r['seconds'], 'threads': r['threads'],
            'us_per_pixel': 1e6 * r['seconds'] / pixels,
        })
    g, o = images[reference['gyoto']], images[reference['grtrace']]
    cross = {'max_difference': float(np.abs(g - o).max() / o.max()), 'flux_difference': float(abs(g.sum() / o.sum() - 1))}
    print(f'{"run":34s} {"max |dI|/peak":>14s} {"|d flux|/flux":>14s} {"seconds":>9s} {"us/pixel":>10s}')
    for row in rows:
        print(f'{row["name"]:34s} {row["max_error"]:14.2e} {row["flux_error"]:14.2e} {row["seconds"]:9.3f} '
              f'{row["us_per_pixel"]:10.2f}')
    print(f'references against each other: max |dI|/peak {cross["max_difference"]:.2e}, '
          f'flux {cross["flux_difference"]:.2e}')
    json.dump({'runs': rows, 'references': cross}, open(runs_json.replace('.json', '-result.json'), 'w'), indent=1)

    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    default_gyoto = next(r['name'] for r in runs if r['code'] == 'gyoto')
    panels = [(f'GYOTO ({default_gyoto})', images[default_gyoto]), ('grtrace (converged)', o),
              (f'GYOTO {default_gyoto} - grtrace', images[default_gyoto] - o)]
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    for ax, (title, im) in zip(axes, panels):
        if 'grtrace' in title and '-' in title:
            lim = np.abs(im).max() or 1.0
            shown = ax.imshow(im, origin='lower', cmap='RdBu_r', vmin=-lim, vmax=lim)
        else:
            shown = ax.imshow(im, origin='lower', cmap='inferno')
        ax.set_title(title, fontsize=10)
        ax.set_xlabel('i')
        ax.set_ylabel('j')
        fig.colorbar(shown, ax=ax, fraction=0.046)
    fig.suptitle('A uniform glowing ball beside a Kerr hole (a = 0.9), GYOTO\'s FixedStar scene', fontsize=11)
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    print(f'wrote {png}')


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit('usage: gyoto_compare.py RUNS.json OUT.png')
    main(sys.argv[1], sys.argv[2])
