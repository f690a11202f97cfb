"""ament_python package backlash_monitor: nodes, cores and the `python -m backlash_monitor` CLI."""
from glob import glob

from setuptools import find_packages, setup

PACKAGE_NAME = "backlash_monitor"

# One entry per executable that `ros2 run backlash_monitor <executable>` finds in lib/backlash_monitor.
EXECUTABLES = {
    "plant_simulator": "backlash_monitor.nodes.plant_simulator:main",
    "windowing": "backlash_monitor.nodes.windowing:main",
    "denoise": "backlash_monitor.nodes.denoise:main",
    "classifier": "backlash_monitor.nodes.classifier:main",
    "width_trend": "backlash_monitor.nodes.width_trend:main",
    "model_watch": "backlash_monitor.nodes.model_watch:main",
    "chain": "backlash_monitor.nodes.chain_container:main",
    "managed_chain": "backlash_monitor.nodes.lifecycle:main_chain",
    "managed_plant": "backlash_monitor.nodes.lifecycle:main_plant",
    "pipeline": "backlash_monitor.nodes.pipeline:main",
    "fleet": "backlash_monitor.nodes.fleet:main",
    "live_view": "backlash_monitor.nodes.live_view:main",
    "record": "backlash_monitor.nodes.record:main",
    "replay": "backlash_monitor.nodes.replay:main",
    "chunk_talker": "backlash_monitor.nodes.chunk_talker:main",
    "chunk_listener": "backlash_monitor.nodes.chunk_listener:main",
}

setup(
    name=PACKAGE_NAME,
    version="0.1.0",
    # foreign_drives/ is the independent drive generator of the tests and benches (docs/foreign_drives.md), not
    # part of the installed package
    packages=find_packages(exclude=["test", "test.*", "foreign_drives", "foreign_drives.*"]),
    data_files=[
        ("share/ament_index/resource_index/packages", ["resource/" + PACKAGE_NAME]),
        ("share/" + PACKAGE_NAME, ["package.xml"]),
        ("share/" + PACKAGE_NAME + "/config", glob("config/*.yaml") + glob("config/*.json")),
        ("share/" + PACKAGE_NAME + "/msg_defs/msg", glob("msg_defs/msg/*.msg")),
    ],
    package_data={PACKAGE_NAME: ["data/*"]},
    install_requires=["setuptools"],
    zip_safe=True,
    maintainer="backlash_monitor maintainers",
    maintainer_email="maintainers@users.noreply.h-seed-6ea24cd3.example",
    description="Online backlash-width identification for electric drives (ROS 2 Jazzy).",
    license="Apache-2.0",
    tests_require=["pytest"],
    entry_points={
        "console_scripts": [f"{name} = {target}" for name, target in EXECUTABLES.items()],
    },
)
