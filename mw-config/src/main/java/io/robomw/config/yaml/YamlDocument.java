package io.robomw.config.yaml;

import org.yaml.snakeyaml.LoaderOptions;
import org.yaml.snakeyaml.Yaml;
import org.yaml.snakeyaml.error.MarkedYAMLException;
import org.yaml.snakeyaml.error.YAMLException;
import org.yaml.snakeyaml.nodes.MappingNode;
import org.yaml.snakeyaml.nodes.Node;

import java.io.IOException;
import java.io.StringReader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * Parses a YAML file into SnakeYAML's node tree, which keeps the line and column of every value,
 * and hands out a {@link MappingReader} on its top-level mapping. Limits: 1 MiB of text, 50 aliases
 * (so an alias bomb cannot exhaust memory), no custom tags (nothing is constructed but plain data).
 */
public final class YamlDocument {

    private static final int MAX_CODE_POINTS = 1 << 20;

    private YamlDocument() {
    }

    /**
     * @param file the file
     * @return a reader on its top-level mapping; check its problems when done
     * @throws io.robomw.config.description.DescriptionException if the file cannot be read or is not YAML
     */
    public static MappingReader read(Path file) {
        String text;
        try {
            text = Files.readString(file, StandardCharsets.UTF_8);
        } catch (IOException e) {
            Problems problems = new Problems(file.toString());
            problems.add(null, "cannot read the file: " + e);
            problems.throwIfAny();
            throw new AssertionError(e);
        }
        return parse(text, file.toString());
    }

    /**
     * @param text   YAML text
     * @param source its name in messages
     * @return a reader on its top-level mapping
     * @throws io.robomw.config.description.DescriptionException if it is not YAML or not a mapping
     */
    public static MappingReader parse(String text, String source) {
        Problems problems = new Problems(source);
        LoaderOptions options = new LoaderOptions();
        options.setCodePointLimit(MAX_CODE_POINTS);
        options.setMaxAliasesForCollections(50);
        options.setAllowDuplicateKeys(false);
        Node root;
        try {
            root = new Yaml(options).compose(new StringReader(text));
        } catch (MarkedYAMLException e) {
            problems.add(e.getProblemMark(), "not valid YAML: " + e.getProblem());
            problems.throwIfAny();
            throw new AssertionError(e);
        } catch (YAMLException e) {
            problems.add(null, "not valid YAML: " + e.getMessage());
            problems.throwIfAny();
            throw new AssertionError(e);
        }
        if (root == null) {
            problems.add(null, "the file is empty; expected a mapping of keys to values");
            problems.throwIfAny();
        }
        if (!(root instanceof MappingNode mapping)) {
            problems.add(root.getStartMark(), "expected a mapping of keys to values at the top of the file");
            problems.throwIfAny();
            throw new AssertionError();
        }
        return new MappingReader(mapping, "", problems);
    }
}
