#!/usr/bin/env python3
"""Checks ros2/litamin2 against idl/litamin2/msg (see ros2_package.cmake).

Usage: ros2_package_check.py PACKAGE_DIR IDL_MSG_DIR
"""
import pathlib
import re
import sys
import xml.etree.ElementTree as ET


def main() -> int:
    package = pathlib.Path(sys.argv[1])
    idl_dir = pathlib.Path(sys.argv[2])
    errors = []
    root = ET.parse(package / "package.xml").getroot()
    name = root.findtext("name")
    modules = set()
    for idl in sorted(idl_dir.glob("*.idl")):
        match = re.search(r"^module\s+(\w+)\s*\{", idl.read_text(), re.M)
        if match:
            modules.add(match.group(1))
    if modules != {name}:
        errors.append(f"package.xml names '{name}', the IDL files' module is {sorted(modules)}")
    if root.get("format") != "3":
        errors.append("package.xml: format 3 expected")
    groups = [g.text for g in root.findall("member_of_group")]
    if "rosidl_interface_packages" not in groups:
        errors.append("package.xml: not a member of rosidl_interface_packages")
    cmake = (package / "CMakeLists.txt").read_text()
    match = re.search(r"set\(litamin2_types([^)]*)\)", cmake)
    listed = set(match.group(1).split()) if match else set()
    present = {p.stem for p in idl_dir.glob("*.idl")}
    if listed != present:
        errors.append(f"CMakeLists.txt lists {sorted(listed)}, idl has {sorted(present)}")
    if f"project({name})" not in cmake:
        errors.append(f"CMakeLists.txt: project({name}) expected")
    for e in errors:
        print("error:", e)
    print(f"{len(present)} types, package {name}: {'ok' if not errors else 'FAILED'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
