"""Reads ubersim's .lcm files: the one parser behind every generator that derives code from the
message definitions (gen_encoded_bounds.py, dds_bridge/gen_dds_bridge.py).

parse_files(paths) -> {type name: Struct}; a Struct has `members` [(type, name, dims)] in
declaration order (dims: the array sizes, numbers or the names of count members) and `constants`
[(type, name, value)].
"""
import re
import sys
from dataclasses import dataclass, field


class LcmSyntaxError(Exception):
    pass


@dataclass
class Struct:
    name: str
    path: str
    members: list = field(default_factory=list)
    constants: list = field(default_factory=list)
    doc: str = ""  # the comment lines just above `struct`, joined
    comments: dict = field(default_factory=dict)  # member or constant name -> its line's comment

    def count_members(self):
        """The members that only give the length of an array (num_* in ubersim)."""
        return {dim for _, _, dims in self.members for dim in dims if not dim.isdigit()}


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def parse_constant(statement, where):
    match = re.fullmatch(r"const\s+(\w+)\s+([A-Za-z_]\w*)\s*=\s*(-?[\w.]+)", statement)
    if not match:
        raise LcmSyntaxError(f"{where}: cannot read constant '{statement}'")
    return match.group(1), match.group(2), match.group(3)


def parse_members(body, where):
    members, constants = [], []
    for statement in body.split(";"):
        statement = " ".join(statement.split())
        if not statement:
            continue
        if statement.startswith("const "):
            constants.append(parse_constant(statement, where))
            continue
        match = re.fullmatch(r"([A-Za-z_][\w.]*)\s+(.+)", statement)
        if not match:
            raise LcmSyntaxError(f"{where}: cannot read member '{statement}'")
        type_name = match.group(1).split(".")[-1]
        for declarator in match.group(2).split(","):
            declarator = declarator.replace(" ", "")
            name_match = re.fullmatch(r"([A-Za-z_]\w*)((?:\[[\w]+\])*)", declarator)
            if not name_match:
                raise LcmSyntaxError(f"{where}: cannot read member '{declarator}'")
            dims = re.findall(r"\[([\w]+)\]", name_match.group(2))
            members.append((type_name, name_match.group(1), dims))
    return members, constants


def line_comments(raw):
    """The comment at the end of each declaration (with the comment lines under it that are
    indented past the declaration: its continuation), by the name it declares."""
    declaration = re.compile(
        r"^(\s*)(?:const\s+)?[\w.]+\s+([A-Za-z_]\w*)[^;/]*;\s*//\s*(.*?)\s*$")
    continuation = re.compile(r"^(\s*)//\s*(.*?)\s*$")
    comments, last, indent = {}, None, 0
    for line in raw.splitlines():
        match = declaration.match(line)
        if match:
            last, indent = match.group(2), len(match.group(1))
            comments[last] = match.group(3)
            continue
        more = continuation.match(line)
        if last and more and len(more.group(1)) > indent:
            comments[last] += " " + more.group(2)
        else:
            last = None
    return comments


def struct_doc(raw, name):
    lines = raw[:raw.index(f"struct {name}")].splitlines()
    doc = []
    while lines and lines[-1].strip().startswith("//"):
        doc.insert(0, lines.pop().strip()[2:].strip())
    return " ".join(doc)


def parse_file(path):
    with open(path, encoding="utf-8") as f:
        raw = f.read()
    text = strip_comments(raw)
    structs = {}
    for match in re.finditer(r"struct\s+([A-Za-z_]\w*)\s*\{(.*?)\}", text, flags=re.S):
        name = match.group(1)
        members, constants = parse_members(match.group(2), f"{path}: struct {name}")
        structs[name] = Struct(name, path, members, constants, struct_doc(raw, name),
                               line_comments(raw))
    if not structs:
        raise LcmSyntaxError(f"{path}: no struct found")
    return structs


def parse_files(paths):
    structs = {}
    for path in paths:
        structs.update(parse_file(path))
    return structs


def dependency_order(structs, roots=None):
    """The types reachable from `roots` (default: all), each after the types it contains."""
    ordered = []

    def add(name, stack):
        if name in ordered:
            return
        if name not in structs:
            raise LcmSyntaxError(f"unknown type {name}")
        if name in stack:
            raise LcmSyntaxError(f"recursive type {name}")
        for type_name, _, _ in structs[name].members:
            if type_name in structs:
                add(type_name, stack + (name,))
        ordered.append(name)

    for root in roots if roots is not None else sorted(structs):
        add(root, ())
    return ordered


def run_generator(argv, usage, generate):
    """The command line of a one-output generator: OUTPUT a.lcm b.lcm ...; `generate(structs)`
    returns the output's text. Exit 2 on a bad command line, 1 on a schema it cannot read."""
    if len(argv) < 3:
        print(usage, file=sys.stderr)
        return 2
    output, paths = argv[1], argv[2:]
    try:
        text = generate(parse_files(paths))
    except LcmSyntaxError as error:
        print(f"{argv[0].rsplit('/', 1)[-1]}: {error}", file=sys.stderr)
        return 1
    with open(output, "w", encoding="utf-8") as f:
        f.write(text)
    return 0
