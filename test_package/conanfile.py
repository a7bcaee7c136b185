# Builds a C and a C++ program against the package through CMakeDeps (find_package(hibi),
# hibi::hibi) and runs both: `conan create` runs this after building the package. Each
# program must need libhibi.so.MAJOR (readelf -d) exactly when the package is the shared one.
import os
from io import StringIO

from conan import ConanFile
from conan.errors import ConanException
from conan.tools.build import can_run
from conan.tools.cmake import CMake, cmake_layout


class HibiTestConan(ConanFile):
    settings = "os", "arch", "compiler", "build_type"
    generators = "CMakeDeps", "CMakeToolchain"

    def requirements(self):
        self.requires(self.tested_reference_str)

    def layout(self):
        cmake_layout(self)

    def build(self):
        cmake = CMake(self)
        cmake.configure()
        cmake.build()

    def test(self):
        if not can_run(self):
            return
        hibi = self.dependencies["hibi"]
        soname = f"libhibi.so.{str(hibi.ref.version).split('.')[0]}"
        for program in ("test_package_c", "test_package_cpp"):
            path = os.path.join(self.cpp.build.bindir, program)
            dynamic = StringIO()
            self.run(f'readelf -d "{path}"', stdout=dynamic)
            needs = f"[{soname}]" in dynamic.getvalue()
            if needs != bool(hibi.options.shared):
                raise ConanException(
                    f"{program} {'needs' if needs else 'does not need'} {soname}, "
                    f"but the package is {'shared' if hibi.options.shared else 'static'}"
                )
            self.run(path, env="conanrun")
