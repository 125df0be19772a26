#!/usr/bin/env python3
"""Merges the usage sections of each component's notes (docs/<component>.md,
the one place they are written) into README.md, between the markers
<!-- BEGIN components --> and <!-- END components -->.
Run it after editing a docs/<component>.md: tools/docs/assemble_readme.py"""
import re, sys, os
root = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
notes = os.path.join(root, 'docs')

def sections(path):
    text = open(path).read().splitlines()
    out = {}
    for i, line in enumerate(text):
        m = re.match(r'^(#+) (.*)$', line)
        if not m: continue
        level = len(m.group(1))
        j = i + 1
        while j < len(text):
            m2 = re.match(r'^(#+) ', text[j])
            if m2 and len(m2.group(1)) <= level: break
            j += 1
        out[m.group(2).strip()] = (level, text[i + 1:j])
    return out

def take(name, heading, new_level=3, title=None):
    path = f'{notes}/{name}.md'
    if not os.path.exists(path): return ''
    secs = sections(path)
    key = next((k for k in secs if k.startswith(heading)), None)
    if key is None:
        print(f'warning: {name}: no section {heading!r}', file=sys.stderr)
        return ''
    level, body = secs[key]
    shifted = []
    for line in body:
        m = re.match(r'^(#+) (.*)$', line)
        if m:
            line = '#' * (len(m.group(1)) - level + new_level) + ' ' + m.group(2)
        shifted.append(line)
    return '#' * new_level + ' ' + (title or key) + '\n' + '\n'.join(shifted).rstrip() + '\n\n'

parts = []
def component(title, doc, intro, pieces):
    if not os.path.exists(f'{notes}/{doc}.md'): return
    parts.append(f'## {title}\n\n{intro} Full design notes, tests and figures: [docs/{doc}.md](docs/{doc}.md).\n\n')
    for heading, *rest in pieces:
        parts.append(take(doc, heading, 3, rest[0] if rest else None))

component('Physics server', 'physics', '`ubersim_physics` owns the ODE world: field, ball and robots built from config files.',
          [('Usage',), ('Pacing modes',), ('Robot types',), ('How to add a robot type',), ('Benchmark',)])
component('Vision emulator', 'vision', '`ubersim_vision` is the overhead-camera vision server, emulated.',
          [('Usage',), ('Profile keys',)])
component('Radio emulator', 'radio', '`ubersim_radio` is each team\'s radio link, emulated.',
          [('Usage',), ('Profiles',), ('Running the real radio server instead',)])
component('Fidelity and speed report', 'report', "A report a user can regenerate: the paper's experiments against the physics the configs claim, and the speed figures. Regenerate it with `tools/report/run_report.sh OUT_DIR` (4-6 min on 2 cores; `--quick` about 1 min). The committed example: [docs/report/report.md](docs/report/report.md), with the by-hand analysis of the misses in [docs/report/analysis.md](docs/report/analysis.md).",
          [('Programs', 'Usage'), ('Findings',)])
component('SSL protocol bridge', 'ssl_bridge', '`ubersim_ssl_bridge` speaks SSL-Vision and the SSL simulation protocol.',
          [('Coming from grSim or the ER-Force simulator',), ('Usage',)])
component('Cyclone DDS bridge (optional)', 'dds_bridge', '`ubersim_dds_bridge` puts ubersim\'s channels on a DDS domain, both ways.',
          [('Building with or without it',), ('Running it',), ('Topic table',), ('ROS 2 notes',)])
component('Live field viewer', 'viewer', '`ubersim_viewer` serves a page that draws the game.',
          [('Watching a game in the browser',), ('Usage',)])

block = '<!-- BEGIN components (merged from docs/) -->\n' + ''.join(parts) + '<!-- END components -->'
readme = open(f'{root}/README.md').read()
if '<!-- BEGIN components' in readme:
    readme = re.sub(r'<!-- BEGIN components.*?<!-- END components -->', lambda m: block, readme, flags=re.S)
else:
    readme = readme.replace('## Folder map', block + '\n\n## Folder map', 1)
open(f'{root}/README.md', 'w').write(readme)
print('README.md: components merged from docs/')
