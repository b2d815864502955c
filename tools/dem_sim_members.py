#!/usr/bin/env python3
"""dem_sim_members.py - renames the uses of struct dem_sim's members that moved into its parts (host/core/sim.h):
`s->nsprings` becomes `s->mesh.nsprings`, `s->skin_now` `s->rows.skin_now`, `s->mc.total` `s->mc.stats.total`.

Only files that include sim.h can see the members (dem.h declares dem_sim opaque), so only they are rewritten, and in
them a use is `NAME->member` where NAME is declared a `dem_sim *` somewhere in the file (`dem_sim *s`, `const dem_sim
*sim`); a file that also declares NAME of another pointer type is named on stderr (the compiler then checks it). The
struct's own declaration in sim.h is not rewritten (it has no `->`).
Running it again changes nothing, so it can be re-run after merging a branch that still uses the old names (a
migration tool: it can go once no branch uses them):

    python3 tools/dem_sim_members.py            # rewrites the .c and .h files under host/ backend/ app/ tests/
                                                # bench/ reference/ common/ that include sim.h, and sim.h
    python3 tools/dem_sim_members.py --check    # lists the files it would change; exit status 1 if any
"""
import re
import sys
from pathlib import Path

# old member -> new path, by part (sim.h: struct sim_mesh, sim_motion, sim_order, sim_rows, sim_mc, sim_trace,
# sim_domain, sim_run, sim_report, sim_scratch)
RENAMES = {}
def part(name, members):
    for old, new in members.items():
        RENAMES[old] = name + '.' + (new or old)

part('mesh', dict.fromkeys(['nsprings', 'spring_cap', 'spring_ij', 'spring_kr', 'ntri', 'tri_cap', 'tri', 'pressure',
                            'npstages', 'pstages', 'pressure_now', 'nhinges', 'hinge_cap', 'hinge', 'hinge_k', 'npatch',
                            'patch_cap', 'patch', 'natt', 'att_cap', 'att']))
part('motion', {'wall_pos': 'pos', 'servo_v': None, 'servo': None, 'servo_sum': None, 'servo_err': None,
                'wall_stage_steps': 'stage_steps', 'stage_cur': None, 'stage_first': None, 'stage_from': None,
                'density_die': None, 'density_other': None, 'particle_volume': None, 'wall_real': 'table',
                'servo_walls': None})
part('order', {'source': None, 'source_n': None, 'reorders': 'count', 'reorder_hold': 'hold', 'reordered': None,
               'reorder_ref': 'ref'})
part('rows', dict.fromkeys(['maxn', 'rebuilds', 'skin_lo', 'skin_hi', 'skin_now', 'skin_extra', 'skin_built', 'maxp',
                            'maxv', 'reach']))
part('mc', {'mc_max_iter': 'max_iter', 'mc_tol': 'tol', 'mc_reach': 'reach', 'mcs_conv': 'stress_conv'})
part('trace', {'seq_step': 'step', 'seq_rebuild': 'rebuild', 'nseq_step': 'nstep', 'nseq_rebuild': 'nrebuild',
               'rebuild_at': None, 'rebuild_len': None})
part('domain', {'lo': None, 'hi': None, 'grid_hi': None, 'grid_cell': None, 'have_domain': 'given'})
part('run', dict.fromkeys(['started', 'step', 'force_step', 'wall_sums_due', 'sample_row']))
part('report', dict.fromkeys(['err', 'err_particle', 'desc', 'build']))
part('scratch', {'scratch_bytes': 'bytes'})
# whole-member moves whose new path starts with the old name: only where the old name is not followed by the part's
# own members (so a second run leaves them alone)
SELF = {'mc': ('mc.stats', ['stats', 'max_iter', 'tol', 'reach', 'stress_conv']),
        'scratch': ('scratch.buf', ['buf', 'bytes'])}

DIRS = ['host', 'backend', 'app', 'tests', 'bench', 'reference', 'common']
OTHER = re.compile(r'\b([A-Za-z_]\w*) \*+(?:const )?([A-Za-z_]\w*)\s*[,;=)]')  # `type *name` declarations
DECL = re.compile(r'\b(?:struct\s+)?dem_sim\s*\*+\s*(?:const\s+)?([A-Za-z_]\w*)')


def rewrite(text, path=''):
    names = set(DECL.findall(text))
    if not names:
        return text
    other = {n for t, n in OTHER.findall(text) if t != 'dem_sim'} & names
    if other:
        print('%s: note: %s may also be of another type here (check the rewrite)' % (path, ', '.join(sorted(other))),
              file=sys.stderr)
    ptr = r'\b(%s)->' % '|'.join(sorted(re.escape(n) for n in names))
    old = '|'.join(sorted(RENAMES, key=len, reverse=True))
    text = re.sub(ptr + r'(%s)\b' % old, lambda m: m.group(1) + '->' + RENAMES[m.group(2)], text)
    for member, (new, inner) in SELF.items():
        text = re.sub(ptr + member + r'\b(?!\.(?:%s)\b)' % '|'.join(inner), lambda m: m.group(1) + '->' + new, text)
    return text


def main():
    check = '--check' in sys.argv[1:]
    root = Path(__file__).resolve().parent.parent
    changed = []
    for d in DIRS:
        for p in sorted((root / d).rglob('*')):
            if p.suffix not in ('.c', '.h') or not p.is_file():
                continue
            text = p.read_text()
            if p.name != 'sim.h' and not re.search(r'#include\s+"sim\.h"', text):
                continue
            new = rewrite(text, p.relative_to(root))
            if new != text:
                changed.append(str(p.relative_to(root)))
                if not check:
                    p.write_text(new)
    for c in changed:
        print(('would change ' if check else 'changed ') + c)
    return 1 if check and changed else 0


if __name__ == '__main__':
    sys.exit(main())
