"""A proof group: which harness, which generated files, which properties,
which engine and depth (``Group``), and the SymbiYosys task it makes on a
folder of generated Verilog (``Group.task``).  The groups themselves are
listed in ``formal/groups.py``.
"""
import re
from dataclasses import dataclass, field
from pathlib import Path

from formal.builds import GENERATED, build_folder
from formal.sby import Task
from rtl.convert import write_whole

PROPS = Path(__file__).resolve().parent / "props"

# The LocalBus write credit (`room`): a unit with the port is proved with the
# promise rules (LOCAL_ROOM), and its FIFO keeps its free places as a
# thermometer instead of a full flag.
CREDIT_REPLACES = ("sync_fifo0_is_full",)
CREDIT_REGISTERS = ("sync_fifo0_free", "sync_fifo0_free_beyond")


def has_write_credit(unit_file):
    """True when the unit's Verilog has the LocalBus ``room`` port."""
    return re.search(r"\blocal_room\b", Path(unit_file).read_text()) is not None


@dataclass
class Group:
    """A set of properties proved together."""

    name: str
    unit: str                 # the generated file (without .v) the proof reads
    harness: list             # property files, the top harness last
    top: str
    keep: tuple               # assertion-name prefixes proved here
    mode: str = "prove"
    depth: int = 20
    parameters: dict = field(default_factory=dict)
    defines: dict = field(default_factory=dict)
    fast: bool = True         # in the default test suite
    text: str = ""
    expose: tuple = ()        # registers of the unit made ports for helper invariants
    includes: tuple = ()      # files the harness includes
    generated: dict = field(default_factory=dict)   # included files written from Python
    convert: object = None    # writes the unit's file into build/formal/generated (not gen/); its path
    build: dict = field(default_factory=dict)   # a build other than gen/'s: its generated files' folder

    def sources(self, gen_dir):
        written = []
        folder = GENERATED / build_folder(self.build) if self.build else GENERATED
        for name, make in self.generated.items():
            folder.mkdir(parents=True, exist_ok=True)
            path = folder / name
            text = make()
            if not path.exists() or path.read_text() != text:
                write_whole(path, text)
            written.append(path)
        unit_file = self.convert() if self.convert else Path(gen_dir) / f"{self.unit}.v"
        return [unit_file, *(PROPS / name for name in self.harness),
                *(PROPS / name for name in self.includes), *written]

    def task(self, gen_dir, unit_file=None):
        """The SymbiYosys task of this group on ``gen_dir`` (``unit_file``
        replaces the unit's file, e.g. a mutant)."""
        sources = self.sources(gen_dir)
        if unit_file is not None:
            sources[0] = Path(unit_file)
        defines = dict(self.defines)
        expose = self.expose
        if has_write_credit(sources[0]):
            defines["LOCAL_ROOM"] = None
            expose = tuple(name for name in expose if name not in CREDIT_REPLACES) + tuple(
                name for name in CREDIT_REGISTERS if any(old in expose for old in CREDIT_REPLACES))
        script = []
        if expose:
            script.append("expose " + " ".join(f"{self.unit}/w:{name}" for name in expose))
        if self.parameters:
            settings = " ".join(f"-set {name} {value}" for name, value in self.parameters.items())
            script.append(f"chparam {settings} {self.top}")
        script.append(f"prep -top {self.top}")
        if self.mode == "cover":
            script.append("chformal -assert -remove")
            if self.keep:   # only the covers named by the prefixes
                keep = " ".join(f"*/n:{prefix}* %d" for prefix in self.keep)
                script.append(f"chformal -cover -remove */t:$check {keep}")
        else:
            keep = " ".join(f"*/n:{prefix}* %d" for prefix in self.keep)
            script.append(f"chformal -assert -remove */t:$check {keep}")
            script.append("chformal -cover -remove")
        reads = [path for path in sources if path.suffix in (".v", ".sv")]
        return Task(name=self.name, mode=self.mode, depth=self.depth, top=self.top,
                    sources=reads, defines=defines, script=script,
                    files=sources)
