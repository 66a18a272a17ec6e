#pragma once
// geotandem's C++ errors as Python exceptions of geotandem.errors (same message: what(), with file,
// line, column and hint), registered once with pybind11's exception translators.

namespace geotandem::python {

// Installs the translator: Cancelled -> KeyboardInterrupt; InvalidArgument -> InvalidArgumentError
// (RecipeError when the error names a line of a text file), IoError -> IoError, FormatError ->
// FormatError, DataError -> DataError, any other geotandem::Error -> Error.
void register_error_translator();

} // namespace geotandem::python
