package io.robomw.cli;

import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Spec;

import java.io.File;
import java.util.concurrent.Callable;

/**
 * {@code mw classpath}: prints the distribution's class path, for IDEs, scripts and
 * {@code java -cp "$(mw classpath)" ...}.
 */
@Command(mixinStandardHelpOptions = true, name = "classpath", description = {"Print the class path of RoboMW's distribution (every module, every driver, the logging binding).",
        "Example: java -cp \"$(./mw classpath):my.jar\" org.example.Main"})
final class ClasspathCommand implements Callable<Integer> {

    @Option(names = "--lines", description = "one entry per line instead of one line separated by the platform's separator (: or ;)")
    boolean lines;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() {
        var out = spec.commandLine().getOut();
        if (lines) {
            DistributionClassPath.entries().forEach(out::println);
        } else {
            out.println(String.join(File.pathSeparator, DistributionClassPath.entries()));
        }
        out.flush();
        return 0;
    }
}
