
TEST_SUITE("packets review render") {
    TEST_CASE("render: engine vs module path, odd sizes, threads, modes, odd pixel loops") {
        static const ModuleTable* table = nullptr;
        struct Loops {
            // reverse order within the tile
            static void reverse(const Tile& tile, const PixelRadiance& radiance,
                                const ImageView& image) {
                for (int j = tile.y1 - 1; j >= tile.y0; --j)
                    for (int i = tile.x1 - 1; i >= tile.x0; --i)
                        image.set(i, j, radiance(table->image_plane_point(i, j, image.width,
                                                                          image.height)));
            }
            // row-major but every pixel asked twice, and the first pixel skipped
            static void twice_skip(const Tile& tile, const PixelRadiance& radiance,
                                   const ImageView& image) {
                for (int j = tile.y0; j < tile.y1; ++j)
                    for (int i = tile.x0; i < tile.x1; ++i) {
                        if (i == tile.x0 && j == tile.y0) continue;
                        const Vec2 uv = table->image_plane_point(i, j, image.width, image.height);
                        image.set(i, j, radiance(uv));
                        image.set(i, j, radiance(uv));
                    }
            }
        };
        const Scene scenes[] = {cornell_box(), translated(cornell_box(), Vec3(1e5f, -3e4f, 2e4f))};
        for (const Scene& scene : scenes)
            for (const auto& wh : {std::pair<int, int>{1, 1}, {17, 3}, {33, 65}, {3, 17}})
                for (const ShadingMode mode :
                     {ShadingMode::normals, ShadingMode::depth, ShadingMode::lambert})
                    for (const int threads : {1, 2, 3}) {
                        RenderSettings s;
                        s.width = wh.first;
                        s.height = wh.second;
                        s.mode = mode;
                        s.threads = threads;
                        Image fast, slow;
                        render(scene, scene.view, s, engine_table(), fast);
                        render(scene, scene.view, s, module_path_table(), slow);
                        INFO(wh.first << "x" << wh.second << " threads " << threads);
                        CHECK(same_bits(fast.pixels.data(), slow.pixels.data(),
                                        fast.pixels.size() * sizeof(fast.pixels[0])));
                        for (int loop = 0; loop < 2; ++loop) {
                            ModuleTable custom = engine_table();
                            custom.render_tile = loop ? &Loops::twice_skip : &Loops::reverse;
                            ModuleTable custom_slow = module_path_table();
                            custom_slow.render_tile = custom.render_tile;
                            table = &custom;
                            Image a, b;
                            render(scene, scene.view, s, custom, a);
                            render(scene, scene.view, s, custom_slow, b);
                            CHECK(same_bits(a.pixels.data(), b.pixels.data(),
                                            a.pixels.size() * sizeof(a.pixels[0])));
                        }
                    }
    }
}
