# Installation and the find_package(Simit CONFIG) package.
