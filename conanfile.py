# Conan 2 recipe for hibi's C library (libhibi.a or libhibi.so, hibi.h, hibi.hpp), built from
# this source tree with cargo and ffi/install: the same libraries `ffi/install` installs, one
# kind per package (the `shared` option). Needs cargo (Rust 1.95 or newer) on PATH and, as
# ffi/install does, bash and GNU binutils: Linux and other ELF systems.
#
#   conan create . --build=missing                  # static, Release
#   conan create . -o hibi/*:shared=True -s build_type=Debug
#
# Cargo fetches the crates hibi-core depends on into CARGO_HOME (default ~/.cargo) unless they
# are there already; with CARGO_NET_OFFLINE=true it uses only what is there (conan/test does).
# Consumers: find_package(hibi) and target hibi::hibi through CMakeDeps, or pkg-config hibi
# through PkgConfigDeps. `conan/test` creates the package offline and builds test_package/.
import os
import re

from conan import ConanFile
from conan.errors import ConanInvalidConfiguration
from conan.tools.files import copy, load
from conan.tools.layout import basic_layout

required_conan_version = ">=2.0"


class HibiConan(ConanFile):
    name = "hibi"
    description = "Crack and cell patterns from three graphics papers (drying mud, glass hit by a ball, skin): the C and C++ API"
    license = "MIT OR Apache-2.0"
    topics = ("procedural", "texture", "crack", "voronoi", "deterministic")
    package_type = "library"
    settings = "os", "arch", "compiler", "build_type"
    options = {"shared": [True, False]}
    default_options = {"shared": False}
    # What cargo needs to build the ffi crate in its workspace: the manifests, the targets the
    # root manifest names (its library and benches), the core's and the ffi crate's sources,
    # and the headers (ffi/install reads the version from hibi.h).
    exports_sources = (
        "Cargo.toml",
        "Cargo.lock",
        "core/*",
        "ffi/*",
        "include/*",
        "cli/Cargo.toml",
        "targets/scenes/Cargo.toml",
        "tests/support/*",
        "benches/*",
        "LICENSE*",
    )

    def set_version(self):
        # The workspace version, which ffi/build.rs and hibi.h's HIBI_VERSION_* also carry.
        manifest = load(self, os.path.join(self.recipe_folder, "Cargo.toml"))
        section = manifest.split("[workspace.package]", 1)[1]
        self.version = re.search(r'^version\s*=\s*"([^"]+)"', section, re.M).group(1)

    def configure(self):
        # rustc builds the library; the C compiler is the consumer's business (a C ABI).
        self.settings.rm_safe("compiler")

    def validate(self):
        if self.settings.os in ("Windows", "Macos", "iOS", "Android", "Emscripten"):
            raise ConanInvalidConfiguration(
                f"this recipe builds with ffi/install (bash, GNU ld and objcopy, ELF): not for {self.settings.os}"
            )

    def layout(self):
        basic_layout(self)

    @property
    def _cargo_profile(self):
        return "dev" if self.settings.build_type == "Debug" else "release"

    def build(self):
        stage = os.path.join(self.build_folder, "stage")
        target = os.path.join(self.build_folder, "target")
        install = os.path.join(self.source_folder, "ffi", "install")
        # Release and MinSizeRel libraries without debug info (symbol tables kept), as the
        # release archives; Debug and RelWithDebInfo keep it.
        strip = " --strip" if self.settings.build_type in ("Release", "MinSizeRel") else ""
        self.run(f'bash "{install}" --prefix "{stage}" --profile {self._cargo_profile} --target-dir "{target}"{strip}')

    def package(self):
        stage = os.path.join(self.build_folder, "stage")
        copy(self, "LICENSE*", self.source_folder, os.path.join(self.package_folder, "licenses"))
        copy(self, "hibi.h*", os.path.join(stage, "include"), os.path.join(self.package_folder, "include"))
        lib = os.path.join(self.package_folder, "lib")
        if self.options.shared:
            # libhibi.so.X.Y.Z, the SONAME link libhibi.so.X and the development link.
            copy(self, "libhibi.so*", os.path.join(stage, "lib"), lib)
        else:
            copy(self, "libhibi.a", os.path.join(stage, "lib"), lib)

    def package_info(self):
        self.cpp_info.libs = ["hibi"]
        self.cpp_info.set_property("cmake_file_name", "hibi")
        self.cpp_info.set_property("cmake_target_name", "hibi::hibi")
        self.cpp_info.set_property("pkg_config_name", "hibi")
        if not self.options.shared:
            # Rust's std in libhibi.a needs these (glibc >= 2.34 has pthread and dl in libc).
            self.cpp_info.system_libs = ["pthread", "dl", "m"]
