// Placeholder translation unit so the library target exists before its sources land.
namespace attenuvis { namespace mie_placeholder { int unused = 0; } }
