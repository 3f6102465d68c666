/* keep_loaded.c - linked into every target of the `asan` preset only (see asan.cmake).
 *
 * The Vulkan loader dlclose()s the ICDs (libvulkan_lvp.so and every other Mesa driver it probes)
 * and layers when an instance is destroyed. Lavapipe keeps a 128-byte block allocated in a
 * pthread_once initialiser during vkEnumeratePhysicalDevices reachable only from its own static
 * data; once the library is unmapped LeakSanitizer no longer scans that data and reports the block
 * as a direct leak from "<unknown module>" frames, which no suppression can name. Measured on
 * Mesa 22.3.6 / loader 1.3.239: keeping only libvulkan_lvp.so loaded makes the report go away, and
 * so does this file. Later loaders offer the same as VK_LOADER_DISABLE_DYNAMIC_LIBRARY_UNLOADING=1
 * (1.3.261+); bookworm's 1.3.239 does not.
 *
 * Defining dlclose in the executable interposes the libc one for every shared library (the loader
 * calls it through its PLT), so libraries stay mapped until exit: LSan scans their data and
 * symbolises their frames, and real leaks in them can then be suppressed by module name in
 * lsan.supp. Nothing in Jade relies on unloading a library.
 */
int dlclose(void* handle)
{
    (void)handle;
    return 0;
}
