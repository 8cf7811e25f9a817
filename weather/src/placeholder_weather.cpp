// Placeholder translation unit so the library target exists before its sources land.
namespace attenuvis { namespace weather_placeholder { int unused = 0; } }
