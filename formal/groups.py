"""The proof groups: which harness, which generated files, which properties,
which engine and depth.

A group keeps the assertions whose names start with one of its prefixes and
drops the others (each property is proved in exactly one group; the covers
run in their own group).  The PCI and card groups read the generated Verilog
of ``gen_dir`` (what users synthesise); the DDA group converts a small-width
build into the work folder.
"""
from dataclasses import dataclass, field
from pathlib import Path

from formal.sby import Task

PROPS = Path(__file__).resolve().parent / "props"
ROOT = Path(__file__).resolve().parent.parent
GEN_DIR = ROOT / "gen"

# The unit's parameters as `python -m rtl.top --convert` writes gen/ by
# default (rtl/top.py PARAMETERS; the card sizes BAR0 from its register table).
PCI_IDS = dict(vendor_id=0x1234, device_id=0xDDA0, revision_id=0x01, class_code=0x088000,
               subsystem_vendor_id=0x1234, subsystem_id=0x0001)


def pci_harness_parameters(io_bits, mem_bits, ids=PCI_IDS):
    """`chparam` settings of pci_target_harness for a target with these BARs and IDs."""
    return dict(IO_BITS=io_bits, MEM_BITS=mem_bits, LOCAL_WIDTH=max(io_bits, mem_bits, 8),
                ID_WORD=ids["device_id"] << 16 | ids["vendor_id"],
                CLASS_WORD=ids["class_code"] << 8 | ids["revision_id"],
                SUBSYSTEM_WORD=ids["subsystem_id"] << 16 | ids["subsystem_vendor_id"])


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

    def sources(self, gen_dir):
        return [Path(gen_dir) / f"{self.unit}.v", *(PROPS / name for name in self.harness)]

    def task(self, gen_dir, unit_file=None):
        """The SymbiYosys task of this group on ``gen_dir`` (``unit_file``
        replaces the unit's file, e.g. a mutant)."""
        sources = self.sources(gen_dir)
        if unit_file is not None:
            sources[0] = Path(unit_file)
        script = []
        if self.parameters:
            settings = " ".join(f"-set {name} {value}" for name, value in self.parameters.items())
            script.append(f"chparam {settings} {self.top}")
        script.append(f"prep -top {self.top}")
        if self.mode == "cover":
            script.append("chformal -assert -remove")
        else:
            keep = " ".join(f"*/n:{prefix}* %d" for prefix in self.keep)
            script.append(f"chformal -assert -remove */t:$check {keep}")
            script.append("chformal -cover -remove")
        return Task(name=self.name, mode=self.mode, depth=self.depth, top=self.top,
                    sources=sources, defines=self.defines, script=script)


PCI_FILES = ["pci_rules.sv", "local_bus_rules.sv", "pci_target_harness.sv"]
PCI_PARAMETERS = pci_harness_parameters(io_bits=6, mem_bits=12)

GROUPS = [
    Group("pci_protocol", "pci_slave", PCI_FILES, "pci_target_harness", ("t_", "lb_"),
          parameters=PCI_PARAMETERS,
          text="PCI 2.3 target rules (pci_rules.sv) and the LocalBus requester rules"),
    Group("pci_config", "pci_slave", PCI_FILES, "pci_target_harness",
          ("config_", "inta_", "target_abort_"), parameters=PCI_PARAMETERS,
          text="configuration space, decode, INTA#, target-abort causes"),
    Group("pci_local", "pci_slave", PCI_FILES, "pci_target_harness", ("write_", "read_"),
          parameters=PCI_PARAMETERS,
          text="the local side carries exactly the PCI transaction"),
    Group("pci_fifo_path", "pci_slave", PCI_FILES, "pci_target_harness",
          ("acknowledged_", "io_not_retried"), parameters=PCI_PARAMETERS,
          text="nothing acknowledged is dropped; I/O never waits behind the FIFO"),
    Group("pci_covers", "pci_slave", PCI_FILES, "pci_target_harness", (), mode="cover", depth=24,
          parameters=PCI_PARAMETERS, text="each kind of transaction is reachable"),
]


def group(name):
    for item in GROUPS:
        if item.name == name:
            return item
    raise ValueError(f"no proof group {name!r}; groups: {', '.join(g.name for g in GROUPS)}")
